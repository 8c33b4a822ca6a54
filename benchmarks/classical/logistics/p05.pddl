; 3 cities x 3 places, 2 airplane(s), 8 packages
(define (problem logistics-c3-l3-a2-p8-s5)
  (:domain logistics)
  (:objects
    city1 city2 city3 - city
    apt1 apt2 apt3 - airport
    pos1-1 pos1-2 pos2-1 pos2-2 pos3-1 pos3-2 - location
    tru1 tru2 tru3 - truck
    apn1 apn2 - airplane
    obj1 obj2 obj3 obj4 obj5 obj6 obj7 obj8 - package
  )
  (:init
    (in-city apt1 city1) (in-city pos1-1 city1) (in-city pos1-2 city1)
    (in-city apt2 city2) (in-city pos2-1 city2) (in-city pos2-2 city2)
    (in-city apt3 city3) (in-city pos3-1 city3) (in-city pos3-2 city3) (at tru1 pos1-2)
    (at tru2 pos2-1) (at tru3 pos3-2) (at apn1 apt2) (at apn2 apt3) (at obj1 pos3-2)
    (at obj2 pos3-1) (at obj3 apt1) (at obj4 pos1-1) (at obj5 pos3-1) (at obj6 apt3)
    (at obj7 apt2) (at obj8 apt2)
  )
  (:goal (and
    (at obj1 apt1) (at obj2 apt2) (at obj3 apt2) (at obj4 apt3) (at obj5 apt2)
    (at obj6 pos1-1) (at obj7 apt1) (at obj8 pos3-1)
  ))
)

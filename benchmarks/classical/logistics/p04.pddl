; 3 cities x 2 places, 1 airplane(s), 6 packages
(define (problem logistics-c3-l2-a1-p6-s4)
  (:domain logistics)
  (:objects
    city1 city2 city3 - city
    apt1 apt2 apt3 - airport
    pos1-1 pos2-1 pos3-1 - location
    tru1 tru2 tru3 - truck
    apn1 - airplane
    obj1 obj2 obj3 obj4 obj5 obj6 - package
  )
  (:init
    (in-city apt1 city1) (in-city pos1-1 city1) (in-city apt2 city2)
    (in-city pos2-1 city2) (in-city apt3 city3) (in-city pos3-1 city3) (at tru1 apt1)
    (at tru2 pos2-1) (at tru3 apt3) (at apn1 apt3) (at obj1 pos2-1) (at obj2 pos1-1)
    (at obj3 apt1) (at obj4 pos2-1) (at obj5 apt2) (at obj6 pos1-1)
  )
  (:goal (and
    (at obj1 apt3) (at obj2 apt1) (at obj3 pos1-1) (at obj4 pos3-1) (at obj5 apt1)
    (at obj6 pos3-1)
  ))
)

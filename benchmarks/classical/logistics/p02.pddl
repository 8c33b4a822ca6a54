; 2 cities x 2 places, 1 airplane(s), 5 packages
(define (problem logistics-c2-l2-a1-p5-s2)
  (:domain logistics)
  (:objects
    city1 city2 - city
    apt1 apt2 - airport
    pos1-1 pos2-1 - location
    tru1 tru2 - truck
    apn1 - airplane
    obj1 obj2 obj3 obj4 obj5 - package
  )
  (:init
    (in-city apt1 city1) (in-city pos1-1 city1) (in-city apt2 city2)
    (in-city pos2-1 city2) (at tru1 apt1) (at tru2 apt2) (at apn1 apt1) (at obj1 apt2)
    (at obj2 apt2) (at obj3 pos1-1) (at obj4 apt1) (at obj5 pos1-1)
  )
  (:goal (and
    (at obj1 apt1) (at obj2 pos1-1) (at obj3 pos2-1) (at obj4 pos2-1) (at obj5 apt2)
  ))
)

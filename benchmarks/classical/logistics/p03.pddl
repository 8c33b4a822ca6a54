; 2 cities x 3 places, 1 airplane(s), 6 packages
(define (problem logistics-c2-l3-a1-p6-s3)
  (:domain logistics)
  (:objects
    city1 city2 - city
    apt1 apt2 - airport
    pos1-1 pos1-2 pos2-1 pos2-2 - location
    tru1 tru2 - truck
    apn1 - airplane
    obj1 obj2 obj3 obj4 obj5 obj6 - package
  )
  (:init
    (in-city apt1 city1) (in-city pos1-1 city1) (in-city pos1-2 city1)
    (in-city apt2 city2) (in-city pos2-1 city2) (in-city pos2-2 city2) (at tru1 apt1)
    (at tru2 pos2-2) (at apn1 apt1) (at obj1 pos1-2) (at obj2 apt2) (at obj3 apt1)
    (at obj4 apt1) (at obj5 pos1-2) (at obj6 pos1-1)
  )
  (:goal (and
    (at obj1 pos2-2) (at obj2 pos2-2) (at obj3 pos2-2) (at obj4 pos2-1)
    (at obj5 pos2-2) (at obj6 pos1-2)
  ))
)

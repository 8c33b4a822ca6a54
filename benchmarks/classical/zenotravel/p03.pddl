; 2 aircraft, 4 persons, 4 cities
(define (problem zenotravel-a2-p4-c4-s3)
  (:domain zeno-travel)
  (:objects
    plane1 plane2 - aircraft
    person1 person2 person3 person4 - person
    city0 city1 city2 city3 - city
    fl0 fl1 fl2 fl3 fl4 fl5 fl6 - flevel
  )
  (:init
    (next fl0 fl1) (next fl1 fl2) (next fl2 fl3) (next fl3 fl4) (next fl4 fl5)
    (next fl5 fl6) (at plane1 city1) (fuel-level plane1 fl5) (at plane2 city2)
    (fuel-level plane2 fl5) (at person1 city0) (at person2 city2) (at person3 city1)
    (at person4 city3)
  )
  (:goal (and
    (at plane2 city0) (at person1 city2) (at person2 city3) (at person3 city0)
    (at person4 city2)
  ))
)

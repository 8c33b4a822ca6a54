; 1 aircraft, 3 persons, 3 cities
(define (problem zenotravel-a1-p3-c3-s2)
  (:domain zeno-travel)
  (:objects
    plane1 - aircraft
    person1 person2 person3 - person
    city0 city1 city2 - city
    fl0 fl1 fl2 fl3 fl4 fl5 fl6 - flevel
  )
  (:init
    (next fl0 fl1) (next fl1 fl2) (next fl2 fl3) (next fl3 fl4) (next fl4 fl5)
    (next fl5 fl6) (at plane1 city0) (fuel-level plane1 fl1) (at person1 city2)
    (at person2 city1) (at person3 city2)
  )
  (:goal (and
    (at plane1 city0) (at person1 city1) (at person2 city0) (at person3 city0)
  ))
)

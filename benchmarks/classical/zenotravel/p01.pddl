; 1 aircraft, 2 persons, 3 cities
(define (problem zenotravel-a1-p2-c3-s1)
  (:domain zeno-travel)
  (:objects
    plane1 - aircraft
    person1 person2 - person
    city0 city1 city2 - city
    fl0 fl1 fl2 fl3 fl4 fl5 fl6 - flevel
  )
  (:init
    (next fl0 fl1) (next fl1 fl2) (next fl2 fl3) (next fl3 fl4) (next fl4 fl5)
    (next fl5 fl6) (at plane1 city0) (fuel-level plane1 fl5) (at person1 city0)
    (at person2 city0)
  )
  (:goal (and
    (at person1 city2) (at person2 city2)
  ))
)

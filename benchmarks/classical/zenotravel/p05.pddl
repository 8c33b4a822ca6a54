; 2 aircraft, 6 persons, 5 cities
(define (problem zenotravel-a2-p6-c5-s5)
  (:domain zeno-travel)
  (:objects
    plane1 plane2 - aircraft
    person1 person2 person3 person4 person5 person6 - person
    city0 city1 city2 city3 city4 - city
    fl0 fl1 fl2 fl3 fl4 fl5 fl6 - flevel
  )
  (:init
    (next fl0 fl1) (next fl1 fl2) (next fl2 fl3) (next fl3 fl4) (next fl4 fl5)
    (next fl5 fl6) (at plane1 city4) (fuel-level plane1 fl3) (at plane2 city4)
    (fuel-level plane2 fl1) (at person1 city1) (at person2 city1) (at person3 city2)
    (at person4 city1) (at person5 city4) (at person6 city4)
  )
  (:goal (and
    (at person1 city0) (at person2 city0) (at person3 city4) (at person4 city4)
    (at person5 city0) (at person6 city1)
  ))
)

; 2 aircraft, 5 persons, 4 cities
(define (problem zenotravel-a2-p5-c4-s4)
  (:domain zeno-travel)
  (:objects
    plane1 plane2 - aircraft
    person1 person2 person3 person4 person5 - person
    city0 city1 city2 city3 - city
    fl0 fl1 fl2 fl3 fl4 fl5 fl6 - flevel
  )
  (:init
    (next fl0 fl1) (next fl1 fl2) (next fl2 fl3) (next fl3 fl4) (next fl4 fl5)
    (next fl5 fl6) (at plane1 city1) (fuel-level plane1 fl3) (at plane2 city3)
    (fuel-level plane2 fl2) (at person1 city3) (at person2 city2) (at person3 city1)
    (at person4 city2) (at person5 city1)
  )
  (:goal (and
    (at plane1 city3) (at plane2 city0) (at person1 city2) (at person2 city0)
    (at person3 city3) (at person4 city1) (at person5 city0)
  ))
)

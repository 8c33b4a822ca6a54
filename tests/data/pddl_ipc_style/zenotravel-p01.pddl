(define (problem ZTRAVEL-1-2)
(:domain zeno-travel)
(:objects plane1 - aircraft
          person1 person2 - person
          city0 city1 city2 - city
          fl0 fl1 fl2 - flevel)
(:init (at plane1 city0) (fuel-level plane1 fl1)
       (at person1 city0) (at person2 city2)
       (next fl0 fl1) (next fl1 fl2))
(:goal (and (at person1 city1) (at person2 city1) (at plane1 city1) (seen person2 city2))))

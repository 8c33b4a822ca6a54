; 4 locations, 3 packages, fuel 3
(define (problem nomystery-l4-p3-s1)
  (:domain transport-strips)
  (:objects
    l0 l1 l2 l3 - location
    level0 level1 level2 level3 - fuellevel
    t0 - truck
    p0 p1 p2 - package
  )
  (:init
    (connected l0 l1) (connected l1 l0) (fuelcost level1 l0 l1) (fuelcost level1 l1 l0)
    (connected l0 l3) (connected l3 l0) (fuelcost level1 l0 l3) (fuelcost level1 l3 l0)
    (connected l2 l3) (connected l3 l2) (fuelcost level2 l2 l3) (fuelcost level2 l3 l2)
    (sum level0 level1 level1) (sum level1 level1 level2) (sum level2 level1 level3)
    (sum level0 level2 level2) (sum level1 level2 level3) (at t0 l0) (fuel t0 level3)
    (at p0 l3) (at p1 l0) (at p2 l3)
  )
  (:goal (and
    (at p0 l1) (at p1 l3) (at p2 l1)
  ))
)

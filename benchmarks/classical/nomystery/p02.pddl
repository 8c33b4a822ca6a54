; 5 locations, 4 packages, fuel 15
(define (problem nomystery-l5-p4-s2)
  (:domain transport-strips)
  (:objects
    l0 l1 l2 l3 l4 - location
    level0 level1 level2 level3 level4 level5 level6 level7 level8 level9 level10
    level11 level12 level13 level14 level15 - fuellevel
    t0 - truck
    p0 p1 p2 p3 - package
  )
  (:init
    (connected l0 l1) (connected l1 l0) (fuelcost level3 l0 l1) (fuelcost level3 l1 l0)
    (connected l0 l4) (connected l4 l0) (fuelcost level2 l0 l4) (fuelcost level2 l4 l0)
    (connected l1 l2) (connected l2 l1) (fuelcost level3 l1 l2) (fuelcost level3 l2 l1)
    (connected l1 l3) (connected l3 l1) (fuelcost level2 l1 l3) (fuelcost level2 l3 l1)
    (connected l1 l4) (connected l4 l1) (fuelcost level3 l1 l4) (fuelcost level3 l4 l1)
    (sum level0 level2 level2) (sum level1 level2 level3) (sum level2 level2 level4)
    (sum level3 level2 level5) (sum level4 level2 level6) (sum level5 level2 level7)
    (sum level6 level2 level8) (sum level7 level2 level9) (sum level8 level2 level10)
    (sum level9 level2 level11) (sum level10 level2 level12)
    (sum level11 level2 level13) (sum level12 level2 level14)
    (sum level13 level2 level15) (sum level0 level3 level3) (sum level1 level3 level4)
    (sum level2 level3 level5) (sum level3 level3 level6) (sum level4 level3 level7)
    (sum level5 level3 level8) (sum level6 level3 level9) (sum level7 level3 level10)
    (sum level8 level3 level11) (sum level9 level3 level12)
    (sum level10 level3 level13) (sum level11 level3 level14)
    (sum level12 level3 level15) (at t0 l2) (fuel t0 level15) (at p0 l0) (at p1 l2)
    (at p2 l2) (at p3 l3)
  )
  (:goal (and
    (at p0 l1) (at p1 l4) (at p2 l4) (at p3 l1)
  ))
)

; 6 locations, 5 packages, fuel 11
(define (problem nomystery-l6-p5-s3)
  (:domain transport-strips)
  (:objects
    l0 l1 l2 l3 l4 l5 - location
    level0 level1 level2 level3 level4 level5 level6 level7 level8 level9 level10
    level11 - fuellevel
    t0 - truck
    p0 p1 p2 p3 p4 - package
  )
  (:init
    (connected l0 l1) (connected l1 l0) (fuelcost level3 l0 l1) (fuelcost level3 l1 l0)
    (connected l0 l2) (connected l2 l0) (fuelcost level1 l0 l2) (fuelcost level1 l2 l0)
    (connected l0 l3) (connected l3 l0) (fuelcost level3 l0 l3) (fuelcost level3 l3 l0)
    (connected l1 l4) (connected l4 l1) (fuelcost level1 l1 l4) (fuelcost level1 l4 l1)
    (connected l2 l3) (connected l3 l2) (fuelcost level1 l2 l3) (fuelcost level1 l3 l2)
    (connected l2 l5) (connected l5 l2) (fuelcost level3 l2 l5) (fuelcost level3 l5 l2)
    (connected l3 l4) (connected l4 l3) (fuelcost level1 l3 l4) (fuelcost level1 l4 l3)
    (sum level0 level1 level1) (sum level1 level1 level2) (sum level2 level1 level3)
    (sum level3 level1 level4) (sum level4 level1 level5) (sum level5 level1 level6)
    (sum level6 level1 level7) (sum level7 level1 level8) (sum level8 level1 level9)
    (sum level9 level1 level10) (sum level10 level1 level11) (sum level0 level3 level3)
    (sum level1 level3 level4) (sum level2 level3 level5) (sum level3 level3 level6)
    (sum level4 level3 level7) (sum level5 level3 level8) (sum level6 level3 level9)
    (sum level7 level3 level10) (sum level8 level3 level11) (at t0 l2)
    (fuel t0 level11) (at p0 l0) (at p1 l3) (at p2 l5) (at p3 l5) (at p4 l3)
  )
  (:goal (and
    (at p0 l3) (at p1 l5) (at p2 l3) (at p3 l3) (at p4 l5)
  ))
)

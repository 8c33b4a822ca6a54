; 7 locations, 6 packages, fuel 9
(define (problem nomystery-l7-p6-s5)
  (:domain transport-strips)
  (:objects
    l0 l1 l2 l3 l4 l5 l6 - location
    level0 level1 level2 level3 level4 level5 level6 level7 level8 level9 - fuellevel
    t0 - truck
    p0 p1 p2 p3 p4 p5 - package
  )
  (:init
    (connected l0 l2) (connected l2 l0) (fuelcost level1 l0 l2) (fuelcost level1 l2 l0)
    (connected l0 l3) (connected l3 l0) (fuelcost level1 l0 l3) (fuelcost level1 l3 l0)
    (connected l0 l4) (connected l4 l0) (fuelcost level1 l0 l4) (fuelcost level1 l4 l0)
    (connected l0 l6) (connected l6 l0) (fuelcost level2 l0 l6) (fuelcost level2 l6 l0)
    (connected l1 l3) (connected l3 l1) (fuelcost level2 l1 l3) (fuelcost level2 l3 l1)
    (connected l1 l5) (connected l5 l1) (fuelcost level1 l1 l5) (fuelcost level1 l5 l1)
    (connected l1 l6) (connected l6 l1) (fuelcost level3 l1 l6) (fuelcost level3 l6 l1)
    (connected l2 l5) (connected l5 l2) (fuelcost level3 l2 l5) (fuelcost level3 l5 l2)
    (connected l3 l4) (connected l4 l3) (fuelcost level3 l3 l4) (fuelcost level3 l4 l3)
    (connected l3 l6) (connected l6 l3) (fuelcost level1 l3 l6) (fuelcost level1 l6 l3)
    (connected l4 l5) (connected l5 l4) (fuelcost level1 l4 l5) (fuelcost level1 l5 l4)
    (connected l5 l6) (connected l6 l5) (fuelcost level3 l5 l6) (fuelcost level3 l6 l5)
    (sum level0 level1 level1) (sum level1 level1 level2) (sum level2 level1 level3)
    (sum level3 level1 level4) (sum level4 level1 level5) (sum level5 level1 level6)
    (sum level6 level1 level7) (sum level7 level1 level8) (sum level8 level1 level9)
    (sum level0 level2 level2) (sum level1 level2 level3) (sum level2 level2 level4)
    (sum level3 level2 level5) (sum level4 level2 level6) (sum level5 level2 level7)
    (sum level6 level2 level8) (sum level7 level2 level9) (sum level0 level3 level3)
    (sum level1 level3 level4) (sum level2 level3 level5) (sum level3 level3 level6)
    (sum level4 level3 level7) (sum level5 level3 level8) (sum level6 level3 level9)
    (at t0 l1) (fuel t0 level9) (at p0 l3) (at p1 l0) (at p2 l3) (at p3 l1) (at p4 l0)
    (at p5 l2)
  )
  (:goal (and
    (at p0 l2) (at p1 l3) (at p2 l1) (at p3 l3) (at p4 l3) (at p5 l5)
  ))
)

; 2 drivers, 3 trucks, 5 packages, 6 locations
(define (problem driverlog-d2-t3-p5-l6-s5)
  (:domain driverlog)
  (:objects
    driver1 driver2 - driver
    truck1 truck2 truck3 - truck
    package1 package2 package3 package4 package5 - obj
    s0 s1 s2 s3 s4 s5 p0-4 p1-3 p2-4 p3-4 p4-5 - location
  )
  (:init
    (link s0 s1) (link s0 s2) (link s0 s4) (link s0 s5) (link s1 s2) (link s1 s3)
    (link s2 s3) (link s2 s4) (link s2 s5) (link s3 s5) (link s1 s0) (link s2 s0)
    (link s4 s0) (link s5 s0) (link s2 s1) (link s3 s1) (link s3 s2) (link s4 s2)
    (link s5 s2) (link s5 s3) (path s0 p0-4) (path p0-4 s0) (path s4 p0-4)
    (path p0-4 s4) (path s1 p1-3) (path p1-3 s1) (path s3 p1-3) (path p1-3 s3)
    (path s2 p2-4) (path p2-4 s2) (path s4 p2-4) (path p2-4 s4) (path s3 p3-4)
    (path p3-4 s3) (path s4 p3-4) (path p3-4 s4) (path s4 p4-5) (path p4-5 s4)
    (path s5 p4-5) (path p4-5 s5) (at driver1 s1) (at driver2 s2) (at truck1 s2)
    (empty truck1) (at truck2 s2) (empty truck2) (at truck3 s4) (empty truck3)
    (at package1 s4) (at package2 s0) (at package3 s2) (at package4 s3)
    (at package5 s1)
  )
  (:goal (and
    (at driver1 s3) (at driver2 s0) (at truck1 s1) (at truck2 s2) (at package1 s2)
    (at package2 s3) (at package3 s3) (at package4 s2) (at package5 s4)
  ))
)

; 2 drivers, 2 trucks, 4 packages, 4 locations
(define (problem driverlog-d2-t2-p4-l4-s3)
  (:domain driverlog)
  (:objects
    driver1 driver2 - driver
    truck1 truck2 - truck
    package1 package2 package3 package4 - obj
    s0 s1 s2 s3 p0-1 p0-2 p1-3 - location
  )
  (:init
    (link s0 s2) (link s0 s3) (link s1 s2) (link s2 s0) (link s3 s0) (link s2 s1)
    (path s0 p0-1) (path p0-1 s0) (path s1 p0-1) (path p0-1 s1) (path s0 p0-2)
    (path p0-2 s0) (path s2 p0-2) (path p0-2 s2) (path s1 p1-3) (path p1-3 s1)
    (path s3 p1-3) (path p1-3 s3) (at driver1 s1) (at driver2 s1) (at truck1 s0)
    (empty truck1) (at truck2 s0) (empty truck2) (at package1 s2) (at package2 s2)
    (at package3 s3) (at package4 s3)
  )
  (:goal (and
    (at driver1 s1) (at driver2 s3) (at truck2 s0) (at package1 s0) (at package2 s1)
    (at package3 s2) (at package4 s1)
  ))
)

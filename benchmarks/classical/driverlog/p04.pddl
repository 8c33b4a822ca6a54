; 3 drivers, 2 trucks, 4 packages, 5 locations
(define (problem driverlog-d3-t2-p4-l5-s4)
  (:domain driverlog)
  (:objects
    driver1 driver2 driver3 - driver
    truck1 truck2 - truck
    package1 package2 package3 package4 - obj
    s0 s1 s2 s3 s4 p0-1 p0-2 p1-3 p1-4 - location
  )
  (:init
    (link s0 s1) (link s0 s3) (link s0 s4) (link s1 s3) (link s1 s4) (link s2 s3)
    (link s3 s4) (link s1 s0) (link s3 s0) (link s4 s0) (link s3 s1) (link s4 s1)
    (link s3 s2) (link s4 s3) (path s0 p0-1) (path p0-1 s0) (path s1 p0-1)
    (path p0-1 s1) (path s0 p0-2) (path p0-2 s0) (path s2 p0-2) (path p0-2 s2)
    (path s1 p1-3) (path p1-3 s1) (path s3 p1-3) (path p1-3 s3) (path s1 p1-4)
    (path p1-4 s1) (path s4 p1-4) (path p1-4 s4) (at driver1 s2) (at driver2 s4)
    (at driver3 s3) (at truck1 s1) (empty truck1) (at truck2 s2) (empty truck2)
    (at package1 s2) (at package2 s2) (at package3 s4) (at package4 s3)
  )
  (:goal (and
    (at driver1 s0) (at driver2 s2) (at driver3 s4) (at truck1 s3) (at truck2 s4)
    (at package1 s0) (at package2 s3) (at package3 s1) (at package4 s4)
  ))
)

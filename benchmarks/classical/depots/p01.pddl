; 1 depot(s), 2 distributors, 2 trucks, 2 crates
(define (problem depots-d1-i2-t2-c2-s1)
  (:domain depots)
  (:objects
    depot0 - depot
    distributor0 distributor1 - distributor
    truck0 truck1 - truck
    pallet0 pallet1 pallet2 - pallet
    crate0 crate1 - crate
    hoist0 hoist1 hoist2 - hoist
  )
  (:init
    (at pallet0 depot0) (at pallet1 distributor0) (at pallet2 distributor1)
    (at hoist0 depot0) (at hoist1 distributor0) (at hoist2 distributor1)
    (available hoist0) (available hoist1) (available hoist2) (at truck0 depot0)
    (at truck1 distributor1) (at crate0 depot0) (on crate0 pallet0)
    (at crate1 distributor0) (on crate1 pallet1) (clear crate0) (clear crate1)
    (clear pallet2)
  )
  (:goal (and
    (on crate0 pallet1) (on crate1 crate0)
  ))
)

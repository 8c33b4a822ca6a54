; 1 depot(s), 2 distributors, 2 trucks, 4 crates
(define (problem depots-d1-i2-t2-c4-s3)
  (:domain depots)
  (:objects
    depot0 - depot
    distributor0 distributor1 - distributor
    truck0 truck1 - truck
    pallet0 pallet1 pallet2 - pallet
    crate0 crate1 crate2 crate3 - crate
    hoist0 hoist1 hoist2 - hoist
  )
  (:init
    (at pallet0 depot0) (at pallet1 distributor0) (at pallet2 distributor1)
    (at hoist0 depot0) (at hoist1 distributor0) (at hoist2 distributor1)
    (available hoist0) (available hoist1) (available hoist2) (at truck0 depot0)
    (at truck1 distributor1) (at crate0 distributor1) (on crate0 pallet2)
    (at crate1 depot0) (on crate1 pallet0) (at crate2 distributor0) (on crate2 pallet1)
    (at crate3 distributor1) (on crate3 crate0) (clear crate1) (clear crate2)
    (clear crate3)
  )
  (:goal (and
    (on crate0 pallet2) (on crate1 pallet0) (on crate2 crate3) (on crate3 pallet1)
  ))
)

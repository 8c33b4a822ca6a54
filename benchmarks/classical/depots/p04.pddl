; 1 depot(s), 2 distributors, 2 trucks, 5 crates
(define (problem depots-d1-i2-t2-c5-s4)
  (:domain depots)
  (:objects
    depot0 - depot
    distributor0 distributor1 - distributor
    truck0 truck1 - truck
    pallet0 pallet1 pallet2 - pallet
    crate0 crate1 crate2 crate3 crate4 - crate
    hoist0 hoist1 hoist2 - hoist
  )
  (:init
    (at pallet0 depot0) (at pallet1 distributor0) (at pallet2 distributor1)
    (at hoist0 depot0) (at hoist1 distributor0) (at hoist2 distributor1)
    (available hoist0) (available hoist1) (available hoist2) (at truck0 depot0)
    (at truck1 distributor0) (at crate0 depot0) (on crate0 pallet0)
    (at crate1 distributor1) (on crate1 pallet2) (at crate2 distributor0)
    (on crate2 pallet1) (at crate3 distributor0) (on crate3 crate2) (at crate4 depot0)
    (on crate4 crate0) (clear crate4) (clear crate3) (clear crate1)
  )
  (:goal (and
    (on crate0 pallet1) (on crate1 pallet2) (on crate2 pallet0) (on crate3 crate0)
    (on crate4 crate2)
  ))
)

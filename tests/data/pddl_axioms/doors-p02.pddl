; Doors r1-r2 (open), r2-r3, r3-r4, r4-r5; behind the door r3-r6 a leak.  The
; key k2 opens both r3-r4 and the leaky r3-r6: opening the wrong one floods
; every room joined to r6 by open doors, the agent's included (a dead end).
; The goal also wants k2 brought back to r1 and r1 dry.
(define (problem doors-p02)
  (:domain doors)
  (:objects r1 r2 r3 r4 r5 r6 - room k1 k2 k3 - key)
  (:init (at r1) (leak r6)
    (open r1 r2) (open r2 r1)
    (door r2 r3) (door r3 r4) (door r4 r5) (door r3 r6)
    (opens k1 r2 r3) (opens k1 r3 r2) (opens k2 r3 r6) (opens k2 r6 r3)
    (opens k2 r3 r4) (opens k2 r4 r3) (opens k3 r4 r5) (opens k3 r5 r4)
    (key-at k1 r2) (key-at k2 r3) (key-at k3 r4))
  (:goal (and (walkable r5) (key-at k2 r1) (not (flooded r1)))))

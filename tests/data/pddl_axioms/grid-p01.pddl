; Two substations feed a line n1-n2-n3-n4; n3 is faulty and powered now
; (through b1, s12, s23): the network trips first.  The goal: every sound
; node powered and nothing tripping.
(define (problem grid-p01)
  (:domain power-grid)
  (:objects sub1 sub2 n1 n2 n3 n4 - node b1 b2 s12 s23 s34 - switch)
  (:init (source sub1) (source sub2) (faulty n3) (breaker b1) (breaker b2)
    (link b1 sub1 n1) (link s12 n1 n2) (link s23 n2 n3) (link s34 n3 n4) (link b2 sub2 n4)
    (closed b1) (closed s12) (closed s23) (closed s34))
  (:goal (and (powered n1) (powered n2) (powered n4) (not (tripping)))))

; A meshed network of eight nodes fed by three substations; two faulty
; nodes; every switch but the breakers closed, so the faults are fed once a
; breaker closes.
(define (problem grid-p02)
  (:domain power-grid)
  (:objects sub1 sub2 sub3 n1 n2 n3 n4 n5 n6 n7 n8 - node
            b1 b2 b3 s12 s23 s34 s45 s56 s67 s78 s15 s38 s26 - switch)
  (:init (source sub1) (source sub2) (source sub3) (faulty n3) (faulty n6)
    (breaker b1) (breaker b2) (breaker b3)
    (link b1 sub1 n1) (link b2 sub2 n4) (link b3 sub3 n8)
    (link s12 n1 n2) (link s23 n2 n3) (link s34 n3 n4) (link s45 n4 n5) (link s56 n5 n6)
    (link s67 n6 n7) (link s78 n7 n8) (link s15 n1 n5) (link s38 n3 n8) (link s26 n2 n6)
    (closed s12) (closed s23) (closed s34) (closed s45) (closed s56) (closed s67)
    (closed s78) (closed s15) (closed s38) (closed s26))
  (:goal (and (powered n1) (powered n2) (powered n4) (powered n5) (powered n7) (powered n8)
              (not (tripping)))))

; The Sussman anomaly.
(define (problem blocks-3-sussman)
  (:domain blocksworld)
  (:objects a b c)
  (:init (clear c) (clear b) (on c a) (ontable a) (ontable b) (handempty))
  (:goal (and (on a b) (on b c))))

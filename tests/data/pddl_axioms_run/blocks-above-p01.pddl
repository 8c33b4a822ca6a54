; Tower a-b-c-d (a on top); the goal: d above a, c above b, and e on the table under nothing.
(define (problem blocks-above-p01)
  (:domain blocks-above)
  (:objects a b c d e)
  (:init (on a b) (on b c) (on c d) (ontable d) (ontable e) (handempty))
  (:goal (and (above d a) (above c b) (above b e) (not (above a e)))))

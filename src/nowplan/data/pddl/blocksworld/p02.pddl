; Reverse a tower of four.
(define (problem blocks-4-reverse)
  (:domain blocksworld)
  (:objects a b c d)
  (:init (clear a) (on a b) (on b c) (on c d) (ontable d) (handempty))
  (:goal (and (on d c) (on c b) (on b a))))

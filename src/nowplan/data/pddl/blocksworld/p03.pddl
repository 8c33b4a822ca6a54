; Two towers of three become one of five plus a block on the table.
(define (problem blocks-6-merge)
  (:domain blocksworld)
  (:objects a b c d e f)
  (:init (clear c) (on c b) (on b a) (ontable a)
         (clear f) (on f e) (on e d) (ontable d)
         (handempty))
  (:goal (and (on a d) (on d b) (on b e) (on e c) (ontable f))))

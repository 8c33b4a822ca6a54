; Seven blocks, everything on the table to start with.
(define (problem blocks-7-build)
  (:domain blocksworld)
  (:objects a b c d e f g)
  (:init (clear a) (clear b) (clear c) (clear d) (clear e) (clear f) (clear g)
         (ontable a) (ontable b) (ontable c) (ontable d) (ontable e) (ontable f) (ontable g)
         (handempty))
  (:goal (and (on g f) (on f e) (on e d) (on c b) (on b a))))

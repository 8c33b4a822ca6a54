; 9 blocks
(define (problem blocks-9-s5)
  (:domain blocksworld)
  (:objects
    a b c d e f g h i
  )
  (:init
    (ontable c) (clear g) (on h c) (on g h) (ontable d) (clear e) (on a d) (on e a)
    (ontable b) (clear b) (ontable i) (clear i) (ontable f) (clear f) (handempty)
  )
  (:goal (and
    (on a b) (on b f) (on c i) (on f h) (on h e) (on i a)
  ))
)

; 7 blocks
(define (problem blocks-7-s4)
  (:domain blocksworld)
  (:objects
    a b c d e f g
  )
  (:init
    (ontable f) (clear b) (on e f) (on g e) (on b g) (ontable d) (clear d) (ontable a)
    (clear c) (on c a) (handempty)
  )
  (:goal (and
    (on b f) (on c b) (on f d) (on g e)
  ))
)

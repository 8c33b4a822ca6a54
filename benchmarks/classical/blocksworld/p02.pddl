; 5 blocks
(define (problem blocks-5-s2)
  (:domain blocksworld)
  (:objects
    a b c d e
  )
  (:init
    (ontable c) (clear c) (ontable b) (clear a) (on a b) (ontable d) (clear d)
    (ontable e) (clear e) (handempty)
  )
  (:goal (and
    (on b a) (on c d)
  ))
)

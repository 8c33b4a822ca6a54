; 4 blocks
(define (problem blocks-4-s1)
  (:domain blocksworld)
  (:objects
    a b c d
  )
  (:init
    (ontable d) (clear a) (on a d) (ontable c) (clear b) (on b c) (handempty)
  )
  (:goal (and
    (on a d) (on d c)
  ))
)

; 6 blocks
(define (problem blocks-6-s3)
  (:domain blocksworld)
  (:objects
    a b c d e f
  )
  (:init
    (ontable a) (clear d) (on d a) (ontable c) (clear c) (ontable f) (clear b) (on e f)
    (on b e) (handempty)
  )
  (:goal (and
    (on a c) (on d e) (on f a)
  ))
)

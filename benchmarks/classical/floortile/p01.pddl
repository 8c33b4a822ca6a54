; 2 x 2 tiles to paint, 1 robot(s)
(define (problem floortile-2x2-r1-s1)
  (:domain floor-tile)
  (:objects
    robot1 - robot
    tile_0-1 tile_0-2 tile_1-1 tile_1-2 tile_2-1 tile_2-2 - tile
    white black - color
  )
  (:init
    (robot-at robot1 tile_0-2) (robot-has robot1 white) (clear tile_0-1)
    (clear tile_1-1) (clear tile_1-2) (clear tile_2-1) (clear tile_2-2)
    (available-color white) (available-color black) (up tile_1-1 tile_0-1)
    (down tile_0-1 tile_1-1) (right tile_0-2 tile_0-1) (left tile_0-1 tile_0-2)
    (up tile_1-2 tile_0-2) (down tile_0-2 tile_1-2) (up tile_2-1 tile_1-1)
    (down tile_1-1 tile_2-1) (right tile_1-2 tile_1-1) (left tile_1-1 tile_1-2)
    (up tile_2-2 tile_1-2) (down tile_1-2 tile_2-2) (right tile_2-2 tile_2-1)
    (left tile_2-1 tile_2-2) (= (total-cost) 0)
  )
  (:goal (and
    (painted tile_1-1 white) (painted tile_1-2 black) (painted tile_2-1 black)
    (painted tile_2-2 white)
  ))
  (:metric minimize (total-cost))
)

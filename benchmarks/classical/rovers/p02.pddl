; 1 rover(s), 5 waypoints, 2 objectives, goals: 2 soil, 1 rock, 1 image(s)
(define (problem rovers-r1-w5-o2-g211-s2)
  (:domain rover)
  (:objects
    rover0 - rover
    rover0store - store
    waypoint0 waypoint1 waypoint2 waypoint3 waypoint4 - waypoint
    camera0 - camera
    colour high_res low_res - mode
    general - lander
    objective0 objective1 - objective
  )
  (:init
    (visible waypoint0 waypoint1) (visible waypoint0 waypoint4)
    (visible waypoint1 waypoint2) (visible waypoint1 waypoint3)
    (visible waypoint1 waypoint4) (visible waypoint1 waypoint0)
    (visible waypoint4 waypoint0) (visible waypoint2 waypoint1)
    (visible waypoint3 waypoint1) (visible waypoint4 waypoint1)
    (at_lander general waypoint4) (channel_free general)
    (can_traverse rover0 waypoint0 waypoint1) (can_traverse rover0 waypoint1 waypoint2)
    (can_traverse rover0 waypoint1 waypoint3) (can_traverse rover0 waypoint1 waypoint4)
    (can_traverse rover0 waypoint1 waypoint0) (can_traverse rover0 waypoint2 waypoint1)
    (can_traverse rover0 waypoint3 waypoint1) (can_traverse rover0 waypoint4 waypoint1)
    (at rover0 waypoint3) (available rover0) (store_of rover0store rover0)
    (empty rover0store) (equipped_for_soil_analysis rover0)
    (equipped_for_rock_analysis rover0) (equipped_for_imaging rover0)
    (on_board camera0 rover0) (calibration_target camera0 objective0)
    (supports camera0 high_res) (supports camera0 low_res)
    (visible_from objective0 waypoint0) (visible_from objective0 waypoint1)
    (visible_from objective0 waypoint2) (visible_from objective0 waypoint4)
    (visible_from objective1 waypoint4) (at_soil_sample waypoint4)
    (at_soil_sample waypoint2) (at_soil_sample waypoint1) (at_rock_sample waypoint1)
    (at_rock_sample waypoint3)
  )
  (:goal (and
    (communicated_soil_data waypoint4) (communicated_soil_data waypoint2)
    (communicated_rock_data waypoint1) (communicated_image_data objective1 low_res)
  ))
)

; 1 rover(s), 4 waypoints, 2 objectives, goals: 1 soil, 1 rock, 1 image(s)
(define (problem rovers-r1-w4-o2-g111-s1)
  (:domain rover)
  (:objects
    rover0 - rover
    rover0store - store
    waypoint0 waypoint1 waypoint2 waypoint3 - waypoint
    camera0 - camera
    colour high_res low_res - mode
    general - lander
    objective0 objective1 - objective
  )
  (:init
    (visible waypoint0 waypoint1) (visible waypoint0 waypoint3)
    (visible waypoint2 waypoint3) (visible waypoint1 waypoint0)
    (visible waypoint3 waypoint0) (visible waypoint3 waypoint2)
    (at_lander general waypoint1) (channel_free general)
    (can_traverse rover0 waypoint0 waypoint1) (can_traverse rover0 waypoint0 waypoint3)
    (can_traverse rover0 waypoint2 waypoint3) (can_traverse rover0 waypoint1 waypoint0)
    (can_traverse rover0 waypoint3 waypoint0) (can_traverse rover0 waypoint3 waypoint2)
    (at rover0 waypoint2) (available rover0) (store_of rover0store rover0)
    (empty rover0store) (equipped_for_soil_analysis rover0)
    (equipped_for_rock_analysis rover0) (equipped_for_imaging rover0)
    (on_board camera0 rover0) (calibration_target camera0 objective1)
    (supports camera0 high_res) (visible_from objective0 waypoint0)
    (visible_from objective0 waypoint1) (visible_from objective1 waypoint0)
    (visible_from objective1 waypoint1) (visible_from objective1 waypoint3)
    (at_soil_sample waypoint3) (at_rock_sample waypoint1) (at_rock_sample waypoint3)
  )
  (:goal (and
    (communicated_soil_data waypoint3) (communicated_rock_data waypoint1)
    (communicated_image_data objective0 high_res)
  ))
)

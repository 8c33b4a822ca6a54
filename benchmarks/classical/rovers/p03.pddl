; 2 rover(s), 6 waypoints, 2 objectives, goals: 2 soil, 2 rock, 1 image(s)
(define (problem rovers-r2-w6-o2-g221-s3)
  (:domain rover)
  (:objects
    rover0 rover1 - rover
    rover0store rover1store - store
    waypoint0 waypoint1 waypoint2 waypoint3 waypoint4 waypoint5 - waypoint
    camera0 - camera
    colour high_res low_res - mode
    general - lander
    objective0 objective1 - objective
  )
  (:init
    (visible waypoint0 waypoint1) (visible waypoint0 waypoint2)
    (visible waypoint0 waypoint3) (visible waypoint1 waypoint4)
    (visible waypoint2 waypoint3) (visible waypoint2 waypoint5)
    (visible waypoint3 waypoint4) (visible waypoint1 waypoint0)
    (visible waypoint2 waypoint0) (visible waypoint3 waypoint0)
    (visible waypoint4 waypoint1) (visible waypoint3 waypoint2)
    (visible waypoint5 waypoint2) (visible waypoint4 waypoint3)
    (at_lander general waypoint5) (channel_free general)
    (can_traverse rover0 waypoint0 waypoint3) (can_traverse rover0 waypoint1 waypoint4)
    (can_traverse rover0 waypoint2 waypoint3) (can_traverse rover0 waypoint2 waypoint5)
    (can_traverse rover0 waypoint3 waypoint4) (can_traverse rover0 waypoint3 waypoint0)
    (can_traverse rover0 waypoint4 waypoint1) (can_traverse rover0 waypoint3 waypoint2)
    (can_traverse rover0 waypoint5 waypoint2) (can_traverse rover0 waypoint4 waypoint3)
    (at rover0 waypoint1) (available rover0) (store_of rover0store rover0)
    (empty rover0store) (equipped_for_soil_analysis rover0)
    (equipped_for_rock_analysis rover0) (equipped_for_imaging rover0)
    (on_board camera0 rover0) (calibration_target camera0 objective0)
    (supports camera0 high_res) (supports camera0 low_res)
    (can_traverse rover1 waypoint0 waypoint2) (can_traverse rover1 waypoint0 waypoint3)
    (can_traverse rover1 waypoint1 waypoint4) (can_traverse rover1 waypoint2 waypoint5)
    (can_traverse rover1 waypoint3 waypoint4) (can_traverse rover1 waypoint2 waypoint3)
    (can_traverse rover1 waypoint2 waypoint0) (can_traverse rover1 waypoint3 waypoint0)
    (can_traverse rover1 waypoint4 waypoint1) (can_traverse rover1 waypoint5 waypoint2)
    (can_traverse rover1 waypoint4 waypoint3) (can_traverse rover1 waypoint3 waypoint2)
    (at rover1 waypoint1) (available rover1) (store_of rover1store rover1)
    (empty rover1store) (visible_from objective0 waypoint1)
    (visible_from objective1 waypoint1) (visible_from objective1 waypoint4)
    (at_soil_sample waypoint4) (at_soil_sample waypoint2) (at_soil_sample waypoint5)
    (at_soil_sample waypoint0) (at_rock_sample waypoint3) (at_rock_sample waypoint5)
  )
  (:goal (and
    (communicated_soil_data waypoint4) (communicated_soil_data waypoint2)
    (communicated_rock_data waypoint3) (communicated_rock_data waypoint5)
    (communicated_image_data objective0 high_res)
  ))
)

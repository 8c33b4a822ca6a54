; 2 satellite(s), 2 instrument(s), 5 images
(define (problem satellite-s2-i2-m3-t5-g5-s4)
  (:domain satellite)
  (:objects
    satellite0 satellite1 - satellite
    instrument0 instrument1 - instrument
    image1 infrared2 spectrograph3 - mode
    star0 star1 star2 phenomenon3 phenomenon4 phenomenon5 phenomenon6 phenomenon7 -
    direction
  )
  (:init
    (on_board instrument0 satellite0) (calibration_target instrument0 star0)
    (supports instrument0 image1) (supports instrument0 spectrograph3)
    (power_avail satellite0) (pointing satellite0 star1)
    (on_board instrument1 satellite1) (calibration_target instrument1 star0)
    (supports instrument1 image1) (supports instrument1 spectrograph3)
    (power_avail satellite1) (pointing satellite1 star1)
  )
  (:goal (and
    (pointing satellite0 phenomenon4) (pointing satellite1 star0)
    (have_image phenomenon5 image1) (have_image phenomenon7 spectrograph3)
    (have_image phenomenon4 spectrograph3) (have_image phenomenon3 spectrograph3)
    (have_image phenomenon4 image1)
  ))
)

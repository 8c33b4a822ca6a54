; 2 satellite(s), 2 instrument(s), 4 images
(define (problem satellite-s2-i2-m3-t4-g4-s3)
  (:domain satellite)
  (:objects
    satellite0 satellite1 - satellite
    instrument0 instrument1 - instrument
    image1 infrared2 spectrograph3 - mode
    star0 star1 star2 phenomenon3 phenomenon4 phenomenon5 phenomenon6 - direction
  )
  (:init
    (on_board instrument0 satellite0) (calibration_target instrument0 star1)
    (supports instrument0 infrared2) (power_avail satellite0)
    (pointing satellite0 phenomenon5) (on_board instrument1 satellite1)
    (calibration_target instrument1 star0) (supports instrument1 infrared2)
    (power_avail satellite1) (pointing satellite1 phenomenon5)
  )
  (:goal (and
    (pointing satellite1 phenomenon6) (have_image phenomenon6 infrared2)
    (have_image phenomenon4 infrared2) (have_image phenomenon3 infrared2)
    (have_image phenomenon5 infrared2)
  ))
)

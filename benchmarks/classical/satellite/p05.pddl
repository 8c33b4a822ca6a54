; 3 satellite(s), 5 instrument(s), 6 images
(define (problem satellite-s3-i2-m3-t6-g6-s5)
  (:domain satellite)
  (:objects
    satellite0 satellite1 satellite2 - satellite
    instrument0 instrument1 instrument2 instrument3 instrument4 - instrument
    image1 infrared2 spectrograph3 - mode
    star0 star1 star2 phenomenon3 phenomenon4 phenomenon5 phenomenon6 phenomenon7
    phenomenon8 - direction
  )
  (:init
    (on_board instrument0 satellite0) (calibration_target instrument0 star2)
    (supports instrument0 spectrograph3) (on_board instrument1 satellite0)
    (calibration_target instrument1 star0) (supports instrument1 infrared2)
    (supports instrument1 spectrograph3) (power_avail satellite0)
    (pointing satellite0 star0) (on_board instrument2 satellite1)
    (calibration_target instrument2 star0) (supports instrument2 image1)
    (supports instrument2 spectrograph3) (power_avail satellite1)
    (pointing satellite1 phenomenon3) (on_board instrument3 satellite2)
    (calibration_target instrument3 star0) (supports instrument3 image1)
    (on_board instrument4 satellite2) (calibration_target instrument4 star1)
    (supports instrument4 infrared2) (power_avail satellite2)
    (pointing satellite2 star2)
  )
  (:goal (and
    (pointing satellite1 phenomenon3) (pointing satellite2 star0)
    (have_image phenomenon5 image1) (have_image phenomenon8 spectrograph3)
    (have_image phenomenon4 spectrograph3) (have_image phenomenon7 infrared2)
    (have_image phenomenon3 spectrograph3) (have_image phenomenon4 infrared2)
  ))
)

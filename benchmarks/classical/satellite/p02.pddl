; 1 satellite(s), 1 instrument(s), 3 images
(define (problem satellite-s1-i2-m3-t4-g3-s2)
  (:domain satellite)
  (:objects
    satellite0 - satellite
    instrument0 - instrument
    image1 infrared2 spectrograph3 - mode
    star0 star1 phenomenon2 phenomenon3 phenomenon4 phenomenon5 - direction
  )
  (:init
    (on_board instrument0 satellite0) (calibration_target instrument0 star1)
    (supports instrument0 image1) (supports instrument0 infrared2)
    (supports instrument0 spectrograph3) (power_avail satellite0)
    (pointing satellite0 phenomenon2)
  )
  (:goal (and
    (have_image phenomenon5 image1) (have_image phenomenon2 image1)
    (have_image phenomenon5 spectrograph3)
  ))
)

; 1 satellite(s), 1 instrument(s), 2 images
(define (problem satellite-s1-i1-m3-t3-g2-s1)
  (:domain satellite)
  (:objects
    satellite0 - satellite
    instrument0 - instrument
    image1 infrared2 spectrograph3 - mode
    star0 star1 phenomenon2 phenomenon3 phenomenon4 - direction
  )
  (:init
    (on_board instrument0 satellite0) (calibration_target instrument0 star0)
    (supports instrument0 spectrograph3) (power_avail satellite0)
    (pointing satellite0 phenomenon3)
  )
  (:goal (and
    (have_image phenomenon3 spectrograph3) (have_image phenomenon4 spectrograph3)
  ))
)

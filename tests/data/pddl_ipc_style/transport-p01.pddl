; a short road (city-loc-1 - city-loc-3 - city-loc-2) and a long one (city-loc-1 - city-loc-2)
(define (problem transport-city-sequential-3nodes-1)
 (:domain transport)
 (:objects city-loc-1 city-loc-2 city-loc-3 - location
           truck-1 - vehicle
           package-1 package-2 - package
           capacity-0 capacity-1 capacity-2 - capacity-number)
 (:init
  (= (total-cost) 0)
  (capacity-predecessor capacity-0 capacity-1)
  (capacity-predecessor capacity-1 capacity-2)
  (road city-loc-1 city-loc-2) (= (road-length city-loc-1 city-loc-2) 50)
  (road city-loc-2 city-loc-1) (= (road-length city-loc-2 city-loc-1) 50)
  (road city-loc-1 city-loc-3) (= (road-length city-loc-1 city-loc-3) 10)
  (road city-loc-3 city-loc-1) (= (road-length city-loc-3 city-loc-1) 10)
  (road city-loc-3 city-loc-2) (= (road-length city-loc-3 city-loc-2) 12)
  (road city-loc-2 city-loc-3) (= (road-length city-loc-2 city-loc-3) 12)
  (at package-1 city-loc-1)
  (at package-2 city-loc-3)
  (at truck-1 city-loc-2)
  (capacity truck-1 capacity-2))
 (:goal (and (at package-1 city-loc-2) (at package-2 city-loc-2)))
 (:metric minimize (total-cost)))

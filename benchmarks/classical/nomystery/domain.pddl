; No-mystery (IPC-2011, "transport-strips"): one truck delivers packages on
; a road map; every drive uses fuel (a per-road amount) from a limited
; supply that is never refilled, so a wasteful route is a dead end.  Fuel is
; encoded with levels and a static (sum ?a ?b ?c) relation, as in the
; original.  Every action costs 1, so the file leaves out :action-costs.
(define (domain transport-strips)
  (:requirements :strips :typing)
  (:types location fuellevel locatable - object
          package truck - locatable)
  (:predicates (connected ?l1 ?l2 - location)
               (at ?o - locatable ?l - location)
               (in ?p - package ?t - truck)
               (fuel ?t - truck ?level - fuellevel)
               (fuelcost ?level - fuellevel ?l1 ?l2 - location)
               (sum ?a ?b ?c - fuellevel))

  (:action load
    :parameters (?p - package ?t - truck ?l - location)
    :precondition (and (at ?t ?l) (at ?p ?l))
    :effect (and (not (at ?p ?l)) (in ?p ?t)))

  (:action unload
    :parameters (?p - package ?t - truck ?l - location)
    :precondition (and (at ?t ?l) (in ?p ?t))
    :effect (and (at ?p ?l) (not (in ?p ?t))))

  (:action drive
    :parameters (?t - truck ?l1 ?l2 - location ?fuelpost ?fueldelta ?fuelpre - fuellevel)
    :precondition (and (connected ?l1 ?l2) (fuelcost ?fueldelta ?l1 ?l2)
                       (fuel ?t ?fuelpre) (sum ?fuelpost ?fueldelta ?fuelpre) (at ?t ?l1))
    :effect (and (not (at ?t ?l1)) (at ?t ?l2)
                 (not (fuel ?t ?fuelpre)) (fuel ?t ?fuelpost))))

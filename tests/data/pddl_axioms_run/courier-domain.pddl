; Couriers (written for nowplan's tests of `nowplan run` with derived predicates).
; A truck reaches a place through roads that are open (a recursive derived
; predicate, read by drive's precondition); a package is delivered where it is
; at its destination (a derived predicate, the goal).  Roads are opened by
; an action, so the hierarchy has three levels: roads, trucks, packages.
(define (domain courier)
  (:requirements :strips :typing :negative-preconditions :derived-predicates
                 :existential-preconditions)
  (:types truck package loc)
  (:predicates
    (road ?a - loc ?b - loc)     ; static: a road that can be opened
    (dest ?p - package ?l - loc) ; static
    (open ?a - loc ?b - loc)
    (at-t ?t - truck ?l - loc)
    (at-p ?p - package ?l - loc)
    (in ?p - package ?t - truck)
    (reach ?t - truck ?l - loc)
    (delivered ?p - package))
  (:derived (reach ?t - truck ?l - loc)
    (or (at-t ?t ?l)
        (exists (?m - loc) (and (reach ?t ?m) (open ?m ?l)))))
  (:derived (delivered ?p - package)
    (exists (?l - loc) (and (at-p ?p ?l) (dest ?p ?l))))
  (:action open-road
    :parameters (?a - loc ?b - loc)
    :precondition (and (road ?a ?b) (not (open ?a ?b)))
    :effect (and (open ?a ?b) (open ?b ?a)))
  (:action drive
    :parameters (?t - truck ?from - loc ?to - loc)
    :precondition (and (at-t ?t ?from) (reach ?t ?to))
    :effect (and (at-t ?t ?to) (not (at-t ?t ?from))))
  (:action load
    :parameters (?p - package ?t - truck ?l - loc)
    :precondition (and (at-p ?p ?l) (at-t ?t ?l))
    :effect (and (in ?p ?t) (not (at-p ?p ?l))))
  (:action unload
    :parameters (?p - package ?t - truck ?l - loc)
    :precondition (and (in ?p ?t) (at-t ?t ?l))
    :effect (and (at-p ?p ?l) (not (in ?p ?t)))))

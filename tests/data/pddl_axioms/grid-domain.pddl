; Restoring power in a distribution network, in the spirit of the IPC-2004
; power supply restoration domain (written for nowplan's tests).  Power
; flows from the substations through closed switches (a recursive derived
; predicate); while a faulty node is powered the network is tripping: only
; breakers may be opened until it stops.
(define (domain power-grid)
  (:requirements :strips :typing :negative-preconditions :derived-predicates
                 :existential-preconditions :disjunctive-preconditions)
  (:types switch node)
  (:predicates
    (source ?n - node)                    ; static: a substation
    (link ?s - switch ?a - node ?b - node) ; static: the switch joins a and b
    (faulty ?n - node)                    ; static
    (breaker ?s - switch)                 ; static
    (closed ?s - switch)
    (powered ?n - node)
    (tripping))
  (:derived (powered ?n - node)
    (or (source ?n)
        (exists (?m - node ?s - switch)
          (and (closed ?s) (powered ?m) (or (link ?s ?m ?n) (link ?s ?n ?m))))))
  (:derived (tripping)
    (exists (?n - node) (and (faulty ?n) (powered ?n))))
  (:action close
    :parameters (?s - switch)
    :precondition (and (not (closed ?s)) (not (tripping)))
    :effect (closed ?s))
  (:action open
    :parameters (?s - switch)
    :precondition (and (closed ?s) (not (tripping)))
    :effect (not (closed ?s)))
  (:action trip
    :parameters (?s - switch)
    :precondition (and (breaker ?s) (closed ?s) (tripping))
    :effect (not (closed ?s))))

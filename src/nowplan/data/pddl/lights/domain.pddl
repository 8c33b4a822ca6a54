; Lights: a night guard walks through a house switching lamps on and off.
; Some rooms are locked and need a key found elsewhere.  Uses negative
; preconditions (switch only a lamp that is off, enter only unlocked rooms),
; equality, and negative goals (lamps that must end up off).
(define (domain lights)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types room lamp key)
  (:predicates (guard-at ?r - room)
               (adjacent ?a - room ?b - room)
               (lamp-in ?l - lamp ?r - room)
               (lit ?l - lamp)
               (locked ?r - room)
               (key-at ?k - key ?r - room)
               (has ?k - key)
               (opens ?k - key ?r - room))

  (:action walk
    :parameters (?from - room ?to - room)
    :precondition (and (guard-at ?from) (adjacent ?from ?to) (not (= ?from ?to)) (not (locked ?to)))
    :effect (and (not (guard-at ?from)) (guard-at ?to)))

  (:action switch-on
    :parameters (?l - lamp ?r - room)
    :precondition (and (guard-at ?r) (lamp-in ?l ?r) (not (lit ?l)))
    :effect (lit ?l))

  (:action switch-off
    :parameters (?l - lamp ?r - room)
    :precondition (and (guard-at ?r) (lamp-in ?l ?r) (lit ?l))
    :effect (not (lit ?l)))

  (:action take-key
    :parameters (?k - key ?r - room)
    :precondition (and (guard-at ?r) (key-at ?k ?r))
    :effect (and (not (key-at ?k ?r)) (has ?k)))

  (:action unlock
    :parameters (?k - key ?from - room ?to - room)
    :precondition (and (guard-at ?from) (adjacent ?from ?to) (has ?k) (opens ?k ?to) (locked ?to))
    :effect (not (locked ?to)))
)

;; ADL: existential, universal and disjunctive preconditions, imply, a disjunctive goal
(define (domain rooms)
  (:requirements :strips :typing :adl)
  (:types room key)
  (:predicates (at ?r - room) (door ?a ?b - room) (locked ?r - room) (opens ?k - key ?r - room)
               (has ?k - key) (key-in ?k - key ?r - room) (lit ?r - room) (alarm))
  (:action go
    :parameters (?a ?b - room)
    :precondition (and (at ?a) (or (door ?a ?b) (door ?b ?a))
                       (imply (locked ?b) (exists (?k - key) (and (has ?k) (opens ?k ?b)))))
    :effect (and (not (at ?a)) (at ?b)))
  (:action grab
    :parameters (?k - key ?r - room)
    :precondition (and (at ?r) (key-in ?k ?r))
    :effect (and (has ?k) (not (key-in ?k ?r))))
  (:action switch-all
    :parameters (?r - room)
    :precondition (and (at ?r) (forall (?k - key) (not (key-in ?k ?r))))
    :effect (and (forall (?s - room) (when (door ?r ?s) (lit ?s)))
                 (when (locked ?r) (alarm)))))

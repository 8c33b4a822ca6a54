; Rooms joined by doors that keys open.  Where the agent can walk is the
; transitive closure of the open doors from its room (a recursive derived
; predicate), except into flooded rooms; water spreads from a leak through
; every open door (another recursive one, a stratum below `walkable`).
(define (domain doors)
  (:requirements :strips :typing :negative-preconditions :derived-predicates)
  (:types room key)
  (:predicates
    (door ?a - room ?b - room)           ; static: a door between a and b
    (opens ?k - key ?a - room ?b - room) ; static: key k opens the door a-b
    (open ?a - room ?b - room)
    (at ?r - room)
    (key-at ?k - key ?r - room)
    (holding ?k - key)
    (leak ?r - room)
    (flooded ?r - room)
    (walkable ?r - room))
  (:derived (flooded ?r - room)
    (or (leak ?r)
        (exists (?s - room) (and (flooded ?s) (open ?s ?r)))))
  (:derived (walkable ?r - room)
    (and (not (flooded ?r))
         (or (at ?r)
             (exists (?s - room) (and (walkable ?s) (open ?s ?r))))))
  (:action open-door
    :parameters (?k - key ?a - room ?b - room)
    :precondition (and (holding ?k) (opens ?k ?a ?b) (walkable ?a) (not (open ?a ?b)))
    :effect (and (open ?a ?b) (open ?b ?a)))
  (:action close-door
    :parameters (?a - room ?b - room)
    :precondition (and (walkable ?a) (open ?a ?b))
    :effect (and (not (open ?a ?b)) (not (open ?b ?a))))
  (:action pick-up
    :parameters (?k - key ?r - room)
    :precondition (and (key-at ?k ?r) (walkable ?r))
    :effect (and (holding ?k) (not (key-at ?k ?r))))
  (:action drop
    :parameters (?k - key ?r - room)
    :precondition (and (holding ?k) (walkable ?r))
    :effect (and (key-at ?k ?r) (not (holding ?k)))))

; Blocksworld with derived predicates (written for nowplan's tests): `clear`
; is derived (nothing on the block and not held), `above` is the transitive
; closure of `on` (recursive); the goal asks for `above`.
(define (domain blocks-above)
  (:requirements :strips :negative-preconditions :derived-predicates :existential-preconditions)
  (:predicates (on ?x ?y) (ontable ?x) (holding ?x) (handempty) (clear ?x) (above ?x ?y))
  (:derived (clear ?x) (and (not (holding ?x)) (not (exists (?y) (on ?y ?x)))))
  (:derived (above ?x ?y) (or (on ?x ?y) (exists (?z) (and (on ?x ?z) (above ?z ?y)))))
  (:action pick-up
    :parameters (?x)
    :precondition (and (clear ?x) (ontable ?x) (handempty))
    :effect (and (not (ontable ?x)) (not (handempty)) (holding ?x)))
  (:action put-down
    :parameters (?x)
    :precondition (holding ?x)
    :effect (and (not (holding ?x)) (handempty) (ontable ?x)))
  (:action stack
    :parameters (?x ?y)
    :precondition (and (holding ?x) (clear ?y))
    :effect (and (not (holding ?x)) (handempty) (on ?x ?y)))
  (:action unstack
    :parameters (?x ?y)
    :precondition (and (on ?x ?y) (clear ?x) (handempty))
    :effect (and (holding ?x) (not (on ?x ?y)) (not (handempty)))))

;; tidybot (IPC-2011) style: object re-declared in :types, constants, negative preconditions
(define (domain TIDYBOT)
  (:requirements :typing :equality :negative-preconditions)
  (:types robot cart object xc yc)
  (:constants cart1 - cart)
  (:predicates (base-pos ?r - robot ?x - xc ?y - yc)
               (object-pos ?o - object ?x - xc ?y - yc)
               (holding ?r - robot ?o - object)
               (gripper-empty ?r - robot)
               (leftof ?x1 - xc ?x2 - xc)
               (on-cart ?o - object))
  (:action move-right
    :parameters (?r - robot ?x1 ?x2 - xc ?y - yc)
    :precondition (and (base-pos ?r ?x1 ?y) (leftof ?x1 ?x2) (not (= ?x1 ?x2)))
    :effect (and (not (base-pos ?r ?x1 ?y)) (base-pos ?r ?x2 ?y)))
  (:action move-left
    :parameters (?r - robot ?x1 ?x2 - xc ?y - yc)
    :precondition (and (base-pos ?r ?x1 ?y) (leftof ?x2 ?x1))
    :effect (and (not (base-pos ?r ?x1 ?y)) (base-pos ?r ?x2 ?y)))
  (:action pick
    :parameters (?r - robot ?o - object ?x - xc ?y - yc)
    :precondition (and (base-pos ?r ?x ?y) (object-pos ?o ?x ?y) (gripper-empty ?r) (not (on-cart ?o)))
    :effect (and (not (object-pos ?o ?x ?y)) (not (gripper-empty ?r)) (holding ?r ?o)))
  (:action put-on-cart
    :parameters (?r - robot ?o - object)
    :precondition (holding ?r ?o)
    :effect (and (not (holding ?r ?o)) (gripper-empty ?r) (on-cart ?o))))

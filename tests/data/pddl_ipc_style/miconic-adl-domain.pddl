;; elevator with conditional effects (miconic ADL, IPC-2000 style): one stop action boards and
;; serves every waiting passenger at once, conditions under forall
(define (domain miconic-adl)
  (:requirements :adl)
  (:types passenger floor)
  (:predicates (origin ?p - passenger ?f - floor) (destin ?p - passenger ?f - floor)
               (above ?f1 ?f2 - floor) (boarded ?p - passenger) (served ?p - passenger)
               (lift-at ?f - floor) (vip ?p - passenger))
  (:action stop
    :parameters (?f - floor)
    :precondition (and (lift-at ?f)
                       (imply (exists (?p - passenger) (and (vip ?p) (not (served ?p))))
                              (exists (?p - passenger) (and (vip ?p) (or (origin ?p ?f) (destin ?p ?f))))))
    :effect (and (forall (?p - passenger)
                   (when (and (boarded ?p) (destin ?p ?f))
                         (and (not (boarded ?p)) (served ?p))))
                 (forall (?p - passenger)
                   (when (and (origin ?p ?f) (not (served ?p)))
                         (boarded ?p)))))
  (:action up
    :parameters (?f1 ?f2 - floor)
    :precondition (and (lift-at ?f1) (above ?f1 ?f2))
    :effect (and (lift-at ?f2) (not (lift-at ?f1))))
  (:action down
    :parameters (?f1 ?f2 - floor)
    :precondition (and (lift-at ?f1) (above ?f2 ?f1))
    :effect (and (lift-at ?f2) (not (lift-at ?f1)))))

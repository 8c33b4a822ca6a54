"""The grounder's achievers read off the problem's ground task (a :class:`Grounder` mixin).

Once a search has built the problem's ground task (:mod:`nowplan.planning.ground_task`: every
instance of every operator, in operator order, with its facts as ids), the achievers of a
generator-free atom need no unification or filling: they are the task's instances adding its
fact (:meth:`TaskAnswers._task_achievers`, per operator).  Where that holds for every operator
of the atom's predicate, the answer is the task's adders of the fact in their order
(:meth:`TaskAnswers.task_answers`), which the compiled regression loop reads in C.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import Atom, Var
from nowplan.core.operators import Action, Operator

if TYPE_CHECKING:
    from nowplan.core.domain import Domain
    from nowplan.planning.ground_task import GroundTask


class TaskAnswers:
    """What :class:`~nowplan.planning.grounding.Grounder` answers from its ground task."""

    # set by the Grounder
    domain: Domain
    memo: bool
    _task: GroundTask | None
    _allobj: frozenset[Any] | None
    _valued: dict[tuple[int, str, Any], int]
    _shared_answers: dict[Atom, list[Action]] | None
    _by_pred: dict[str, list[tuple[int, Operator, tuple[Atom, ...]]]]
    _gen_by_pred_nonempty: frozenset[str]

    def objects_of(self, t: str | None) -> list[str]:
        raise NotImplementedError

    def use_task(self, task: GroundTask) -> None:
        """Answer generator-free achievers from ``task`` (this problem's ground task, same static facts)."""
        self._task = task

    def task_answers(self, target: Atom, task: GroundTask) -> bool:
        """Are ``target``'s achievers, for every call of this problem, exactly ``task``'s actions that add
        its fact, in the task's order?  (The compiled regression loop then reads them off the task.)

        So where the answer is shared (no generator achieves the atom, nor has an effect of its
        predicate), ``task`` is the one this grounder answers from and it answers for every
        operator (:meth:`_task_achievers`: one effect at most that may give the atom); the task's
        actions are grouped by operator in the order of ``_by_pred``'s entries.
        """
        if task is not self._task or not self.memo or self._shared_answers is None:
            return False
        pred = target.predicate
        if pred in self._gen_by_pred_nonempty or self._task_fact(target) is None:
            return False
        value = target.value
        for i, _op, effs in self._by_pred.get(pred, ()):
            key = (i, pred, value)
            n = self._valued.get(key)
            if n is None:
                n = self._valued[key] = sum(1 for e in effs if isinstance(e.value, Var) or e.value == value)
            if n > 1:
                return False
        return True

    def _task_fact(self, target: Atom) -> int | None:
        """``target``'s fact id where the ground task can answer for it (an equality fact of a boolean
        value whose arguments all name objects), else ``None``."""
        T = self.domain.facts
        f = T.by_key.get((target.predicate, target.args, target.value))
        if f is None or not T.equality[f] or not isinstance(target.value, bool):
            return None
        allobj = self._all_objects()
        if not all(isinstance(a, str) and a in allobj for a in target.args):
            return None
        return f

    def _task_groups(self, target: Atom) -> dict[int, list[int]] | None:
        """The ground task's actions that add ``target``'s fact, by operator index (ascending within one),
        or ``None`` where the task cannot answer for ``target`` (see :meth:`_task_achievers`)."""
        task = self._task
        f = self._task_fact(target)
        if task is None or f is None:
            return None
        op_of = task.op
        groups: dict[int, list[int]] = {}
        for k in task.adders().get(f, ()):
            g = groups.get(op_of[k])
            if g is None:
                groups[op_of[k]] = [k]
            else:
                g.append(k)
        return groups

    def _task_achievers(
        self, i: int, effs: tuple[Atom, ...], target: Atom, groups: dict[int, list[int]]
    ) -> list[Action] | None:
        """Operator ``i``'s achievers of ``target`` read off the ground task, or ``None`` where it cannot answer.

        The task holds every instance ``_fill(op, {})`` makes, in its order, and
        ``_fill(op, b)`` makes those that agree with ``b`` in the same order; so
        where one effect of ``op`` can unify with ``target``, its value rule is
        equality and every argument names an object (a value that is no object
        passes the type check in ``_fill`` but is in no instance of the task),
        the instances adding ``target``'s fact are the achievers, in order
        (``groups``: :meth:`_task_groups`, which checks the fact and its arguments).
        """
        key = (i, target.predicate, target.value)
        n = self._valued.get(key)
        if n is None:
            n = self._valued[key] = sum(1 for e in effs if isinstance(e.value, Var) or e.value == target.value)
        if n == 0:
            return []  # no effect of the operator has the value (equality): nothing to unify
        if n != 1:
            return None
        task = self._task
        assert task is not None
        action = task.action
        return [action(k) for k in groups.get(i, ())]

    def _all_objects(self) -> frozenset[Any]:
        if self._allobj is None:
            self._allobj = frozenset(self.objects_of(None))
        return self._allobj

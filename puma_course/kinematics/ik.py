"""The one inverse-kinematics result type shared by every robot, and the rules around it.

Policy (the same for every robot of the course):

* ``robot.ik(T)`` returns an :class:`IKSolutions`: every configuration reaching T, one row
  each, with a branch label and the singularities it sits at. An **unreachable pose is not an
  error**: the result has ``success`` False, no rows, and a ``reason`` in words; it never
  contains NaN. Bad input (not a rigid transform, NaN, complex, ...) raises ``ValueError``.
* ``robot.ik_batch(Ts)`` returns an :class:`IKBatch`: every branch for N poses at once,
  a ``valid`` mask, and zeros (never NaN) where a branch does not exist.
* Revolute joints come back wrapped to (-π, π] (:func:`puma_course.transforms.wrap_angle`).
* At a singular pose one representative per branch is returned (the one nearest ``near``
  when given); each row names its singularities with machine-readable keys whose sentences
  are in :attr:`IKSolutions.messages`, and ``ik`` emits a :class:`SingularityWarning`.
"""

from __future__ import annotations

import html
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array
from ..transforms import wrap_angle
from .ik_select import (  # noqa: F401 - their old home: robots, trajectories and tests import them from here
    dedupe_mask,
    joint_distance,
    keep_start,
    keys_from_bits,
    nearest_index,
    revolute_mask,
)

__all__ = [
    "KinematicsWarning",
    "SingularityWarning",
    "IKSolutions",
    "IKBatch",
    "joint_distance",
    "keys_from_bits",
]


class KinematicsWarning(UserWarning):
    """Base of the package's kinematics warnings."""


class SingularityWarning(KinematicsWarning):
    """A pose reached at a singular configuration: some joints are not uniquely defined, a
    representative was chosen (see the solutions' ``flags`` and ``messages``)."""


@dataclass(frozen=True, eq=False)
class IKSolutions(Sequence[np.ndarray]):
    """Every configuration reaching one pose: behaves like the (k, n) array ``q``.

    ``labels[i]`` names the branch of ``q[i]``; ``flags[i]`` the singularities it sits at
    (machine-readable keys, explained in ``messages``). ``success`` is False only when no
    configuration reaches the pose; ``reason`` then says why (and ``q`` has no rows).

    >>> sol = IKSolutions(np.zeros((1, 2)), ("elbow up",), (("elbow",),), {"elbow": "the arm is stretched"})
    >>> len(sol), sol.success, sol.singular, sol.messages["elbow"]
    (1, True, ('elbow',), 'the arm is stretched')
    >>> none = IKSolutions(np.zeros((0, 2)), (), (), success=False, reason="out of reach")
    >>> none.success, none.reason, len(none)
    (False, 'out of reach', 0)
    """

    q: np.ndarray
    labels: tuple[str, ...] = ()
    flags: tuple[tuple[str, ...], ...] = ()
    messages: Mapping[str, str] = field(default_factory=dict)
    success: bool = True
    reason: str = ""
    robot: str = ""
    method: str = ""
    revolute: np.ndarray | None = None
    #: how the lectures write the joint variables (θ1, ..., or α1, α2, q2, ...): the display's column names
    joints: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        # finite, real, and no larger than joint values are (issue 21: rows of 1e300 were accepted)
        q = np.array(as_array(self.q, "q", what="solutions of shape (k, n)", max_magnitude=MAX_MAGNITUDE), dtype=float)
        if q.ndim != 2:
            raise ValueError(f"q: expected solutions of shape (k, n), got an array of shape {q.shape}")
        k = len(q)
        labels = tuple(self.labels) if self.labels else tuple(f"solution {i + 1}" for i in range(k))
        flags = tuple(tuple(f) for f in self.flags) if self.flags else ((),) * k
        if len(labels) != k or len(flags) != k:
            raise ValueError(f"labels, flags: expected one per solution ({k}), got {len(labels)} and {len(flags)}")
        q.setflags(write=False)
        object.__setattr__(self, "q", q)
        object.__setattr__(self, "labels", labels)
        object.__setattr__(self, "flags", flags)
        object.__setattr__(self, "messages", dict(self.messages))
        object.__setattr__(self, "revolute", revolute_mask(self.revolute, q.shape[1]))
        joints = tuple(self.joints) if self.joints else tuple(f"q{j + 1}" for j in range(q.shape[1]))
        if len(joints) != q.shape[1]:
            raise ValueError(f"joints: expected {q.shape[1]} joint names, got {len(joints)}")
        object.__setattr__(self, "joints", joints)

    # ---- array-like -------------------------------------------------------------------
    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return self.q.copy() if dtype is None else self.q.astype(dtype)

    def __len__(self) -> int:
        return len(self.q)

    def __getitem__(self, i: Any) -> Any:
        if not self.success:
            raise IndexError(f"no solution to index: {self.reason}")
        return self.q[i]

    def __iter__(self) -> Iterator[np.ndarray]:
        return iter(self.q)

    @property
    def shape(self) -> tuple[int, ...]:
        """(k, n): k solutions of n joints."""
        return tuple(self.q.shape)

    # ---- singularities ----------------------------------------------------------------
    @property
    def singular(self) -> tuple[str, ...]:
        """Every singularity key met by any solution, in first-seen order."""
        seen: list[str] = []
        for f in self.flags:
            seen += [k for k in f if k not in seen]
        return tuple(seen)

    @property
    def is_singular(self) -> bool:
        """True when any solution sits at a singularity."""
        return bool(self.singular)

    # ---- choosing -----------------------------------------------------------------------
    def nearest(self, q_ref: Any) -> np.ndarray:
        """The solution closest to ``q_ref`` (wrapped joint distance); ValueError if there is none."""
        ref = as_array(q_ref, "q_ref", (self.q.shape[1],), what=f"a joint vector of shape ({self.q.shape[1]},)")
        if not self.success or len(self.q) == 0:
            raise ValueError(f"q_ref: there is no solution to choose from ({self.reason or 'empty'})")
        assert self.revolute is not None
        return self.q[int(nearest_index(self.q, ref, self.revolute))].copy()

    def sorted_by(self, q_ref: Any) -> IKSolutions:
        """The same solutions sorted by distance to ``q_ref``, nearest first (stable)."""
        ref = as_array(q_ref, "q_ref", (self.q.shape[1],), what=f"a joint vector of shape ({self.q.shape[1]},)")
        return self._sorted(ref)

    def _sorted(self, ref: np.ndarray) -> IKSolutions:
        """:meth:`sorted_by` for a validated reference (the hot path of every ``ik(T, near=...)``)."""
        if len(self.q) < 2:
            return self
        assert self.revolute is not None
        d = self.q - ref
        d = np.where(self.revolute, wrap_angle(d), d)
        order = np.argsort(np.round(np.einsum("kj,kj->k", d, d), 28), kind="stable").tolist()
        if order == list(range(len(order))):
            return self
        new = object.__new__(IKSolutions)  # the fields are already checked: skip __post_init__
        q = self.q[order]
        q.setflags(write=False)
        for name, value in vars(self).items():
            object.__setattr__(new, name, value)
        object.__setattr__(new, "q", q)
        object.__setattr__(new, "labels", tuple(self.labels[i] for i in order))
        object.__setattr__(new, "flags", tuple(self.flags[i] for i in order))
        return new

    def within_limits(self, qlim: Any) -> IKSolutions:
        """Only the solutions with every joint inside ``qlim`` ((n, 2): lower, upper; bounds included).

        A revolute angle is inside when it, or it plus whole turns, lies in its range (the PUMA-560's θ2
        runs from -225° to 45°: :mod:`~puma_course.kinematics.joint_limits`); a kept row carries the
        value inside the range (as returned when that is inside; fk is 2π-periodic). Prismatic joints
        are compared as they are. With no row left, ``success`` is False and ``reason`` names the
        joints that stopped each branch.

        >>> sol = IKSolutions(np.array([[0.5, 2.0], [0.5, -2.0]]), ("up", "down"))
        >>> kept = sol.within_limits([[-1.0, 1.0], [-2.5, 0.0]])
        >>> kept.labels, kept.success
        (('down',), True)
        >>> sol.within_limits([[-1.0, 1.0], [-1.0, 1.0]]).reason
        'no solution within the joint limits (up: q2; down: q2)'
        >>> turned = sol.within_limits([[-1.0, 1.0], [1.0, 5.0]])  # -2.0 + 2π = 4.28 lies in [1, 5]
        >>> turned.labels, np.round(turned.q[:, 1], 4).tolist()
        (('up', 'down'), [2.0, 4.2832])
        """
        n = self.q.shape[1]
        lim = as_array(qlim, "qlim", (n, 2), what=f"joint limits of shape ({n}, 2), lower then upper")
        if np.any(lim[:, 0] > lim[:, 1]):
            raise ValueError(f"qlim: expected each lower limit at most its upper limit, got {lim.tolist()}")
        lo, hi = lim[:, 0], lim[:, 1]
        assert self.revolute is not None
        as_is = (self.q >= lo) & (self.q <= hi)
        # a revolute angle outside its range: the first turn of it at or above the lower limit
        turned = self.q + 2.0 * np.pi * np.ceil((lo - self.q) / (2.0 * np.pi))
        use_turn = self.revolute & ~as_is & (turned <= hi)
        outside = ~as_is & ~use_turn
        keep: np.ndarray = ~np.any(outside, axis=1)
        if keep.all() and not use_turn.any():
            return self
        new = object.__new__(IKSolutions)
        for name, value in vars(self).items():
            object.__setattr__(new, name, value)
        q = np.where(use_turn, turned, self.q)[keep]
        q.setflags(write=False)
        object.__setattr__(new, "q", q)
        object.__setattr__(new, "labels", tuple(lb for lb, k in zip(self.labels, keep, strict=True) if k))
        object.__setattr__(new, "flags", tuple(f for f, k in zip(self.flags, keep, strict=True) if k))
        if not keep.any() and self.success:
            stops = "; ".join(
                f"{lb}: " + ", ".join(self.joints[j] for j in np.flatnonzero(row))
                for lb, row in zip(self.labels, outside, strict=True)
            )
            object.__setattr__(new, "success", False)
            object.__setattr__(new, "reason", f"no solution within the joint limits ({stops})")
        return new

    # ---- display ------------------------------------------------------------------------
    def __repr__(self) -> str:
        what = f"{self.robot} " if self.robot else ""
        how = f" ({self.method})" if self.method else ""
        if not self.success:
            return f"IKSolutions: {what}pose unreachable{how}: {self.reason}"
        lines = [f"IKSolutions: {what}{len(self.q)} solution(s){how}" + (" [singular]" if self.singular else "")]
        width = max((len(lab) for lab in self.labels), default=0)
        for lab, row, f in zip(self.labels, self.q, self.flags, strict=True):
            values = " ".join(f"{v:8.4f}" for v in np.round(row, 4) + 0.0)  # fixed width: rows line up
            note = f"  singular: {', '.join(f)}" if f else ""
            lines.append(f"  {lab:<{width}}  q = [{values}]{note}")
        lines += [f"  {k}: {self.messages[k]}" for k in self.singular if k in self.messages]
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        if not self.success:
            return f"<p><b>Unreachable</b>: {html.escape(self.reason)}</p>"
        assert self.revolute is not None
        head = "".join(
            f"<th>{html.escape(name, quote=False)}{' [deg]' if r else ''}</th>"
            for name, r in zip(self.joints, self.revolute, strict=True)
        )
        rows = []
        for lab, row, f in zip(self.labels, self.q, self.flags, strict=True):
            cells = "".join(
                f"<td>{np.degrees(v) if r else v:.3f}</td>" for v, r in zip(row, self.revolute, strict=True)
            )
            rows.append(f"<tr><td>{html.escape(lab)}</td>{cells}<td>{html.escape(', '.join(f))}</td></tr>")
        notes = "".join(
            f"<li><b>{html.escape(k)}</b>: {html.escape(self.messages.get(k, ''))}</li>" for k in self.singular
        )
        return (
            f"<table><caption>{html.escape(self.robot, quote=False)} IK: {len(self.q)} solution(s)</caption>"
            f"<thead><tr><th>branch</th>{head}<th>singular</th></tr></thead><tbody>{''.join(rows)}</tbody></table>"
            + (f"<ul>{notes}</ul>" if notes else "")
        )


@dataclass(frozen=True, eq=False)
class IKBatch:
    """Every branch for N poses (see ``robot.ik_batch``).

    ``q`` (N, k, n): branch j of pose i, in the fixed branch order ``labels`` (k); revolute
    joints wrapped to (-π, π]. ``valid`` (N, k): the branch reaches the pose and is not a
    duplicate of an earlier branch at a singularity. ``flags`` (N, k): bit masks of
    singularities, bit b standing for ``flag_keys[b]`` (sentences in ``messages``).
    ``reason`` (N,): "" or why the pose cannot be reached. Entries of missing branches are 0,
    never NaN.
    """

    q: np.ndarray
    valid: np.ndarray
    labels: tuple[str, ...]
    flags: np.ndarray
    flag_keys: tuple[str, ...]
    messages: Mapping[str, str]
    reason: np.ndarray
    robot: str = ""
    method: str = ""
    revolute: np.ndarray | None = None
    joints: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        N, k, n = self.q.shape
        if self.valid.shape != (N, k) or self.flags.shape != (N, k) or len(self.labels) != k:
            raise ValueError("valid, flags, labels: expected shapes (N, k), (N, k) and k matching q (N, k, n)")
        object.__setattr__(self, "revolute", revolute_mask(self.revolute, n))

    def __len__(self) -> int:
        return int(self.q.shape[0])

    @property
    def reachable(self) -> np.ndarray:
        """(N,) True where the pose can be reached."""
        return self.reason == ""

    def keys(self, i: int, j: int) -> tuple[str, ...]:
        """The singularity keys of branch ``j`` of pose ``i``."""
        return keys_from_bits(int(self.flags[i, j]), self.flag_keys)

    def solutions(self, i: int) -> IKSolutions:
        """Pose ``i`` as an :class:`IKSolutions` (its valid branches, in branch order)."""
        keep = np.flatnonzero(self.valid[i])
        if not self.reachable[i]:
            return IKSolutions(
                np.zeros((0, self.q.shape[2])), (), (), self.messages, False, str(self.reason[i]),
                self.robot, self.method, self.revolute, self.joints,
            )  # fmt: skip
        flags = tuple(self.keys(i, int(j)) for j in keep)
        present = {k for f in flags for k in f}
        return IKSolutions(
            self.q[i, keep],
            tuple(self.labels[j] for j in keep),
            flags,
            {k: v for k, v in self.messages.items() if k in present},
            True,
            "",
            self.robot,
            self.method,
            self.revolute,
            self.joints,
        )

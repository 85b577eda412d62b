"""The robot API every arm of the course implements (PUMA-560, MK3, Porter's chain, the three-step arm).

A :class:`Robot` knows its joints (``n``, ``revolute``, ``qlim``, named ``configurations``),
computes the pose of its end effector (``fk``), every frame for drawing (``frames``) and the
polyline of its links (``points``), and solves the inverse problem (``ik`` for one pose,
``ik_batch`` for many; the result types are in :mod:`puma_course.kinematics.ik`).

Batches put the batch axis first: q of shape (N, n) gives (N, 4, 4).
"""

from __future__ import annotations

import html
import math
import warnings
from abc import ABC, abstractmethod
from collections.abc import Mapping
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_count, as_transform
from .ik import IKBatch, IKSolutions, SingularityWarning

__all__ = ["Robot", "MountedFk"]


class Robot(ABC):
    """Base class of the course's arms: the shared joint bookkeeping and the shape of the API.

    Subclasses set ``name``, ``units``, ``revolute`` (boolean mask), ``qlim`` ((n, 2) limits
    used by sliders), ``configurations`` (named joint vectors), ``joint_symbols`` (how the
    lectures write the joint variables) and implement ``fk``, ``frames``, ``ik``, ``ik_batch``
    and ``parameters`` (the constants shown by ``_repr_html_``). ``joint_limits`` holds an arm's
    published joint ranges ((n, 2), radians, for ``IKSolutions.within_limits``) where a source gives
    them, else None.
    """

    name: str = "robot"
    units: str = ""
    revolute: np.ndarray
    qlim: np.ndarray
    joint_limits: np.ndarray | None = None
    configurations: dict[str, np.ndarray]
    joint_symbols: tuple[str, ...]

    # ---- joints ------------------------------------------------------------------------
    @property
    def n(self) -> int:
        """Number of joints."""
        return int(len(self.revolute))

    def _init_joints(
        self,
        revolute: Any,
        configurations: Mapping[str, Any],
        qlim: Any = None,
        joint_symbols: Any = None,
    ) -> None:
        rev = np.array(revolute, dtype=bool)
        rev.setflags(write=False)
        self.revolute = rev
        n = len(rev)
        if qlim is None:
            qlim = [(-math.pi, math.pi)] * n
        lim = as_array(qlim, "qlim", (n, 2), what=f"joint limits of shape ({n}, 2)")
        if np.any(lim[:, 0] >= lim[:, 1]):
            raise ValueError(f"qlim: expected each lower limit below its upper limit, got {lim.tolist()}")
        lim.setflags(write=False)
        self.qlim = lim
        self.joint_symbols = tuple(joint_symbols) if joint_symbols else tuple(f"q{i + 1}" for i in range(n))
        self.configurations = {}
        if not isinstance(configurations, Mapping) or not all(isinstance(k, str) for k in configurations):
            got = f"{type(configurations).__name__} {configurations!r}"[:120]
            raise ValueError(f"configurations: expected a mapping of names to joint vectors, got {got}")
        for key, value in configurations.items():
            q = self.check_q(value, f"configurations[{key!r}]")
            if q.ndim != 1:
                raise ValueError(f"configurations[{key!r}]: expected one joint vector of shape ({n},)")
            q.setflags(write=False)
            self.configurations[key] = q

    def check_q(self, q: Any, name: str = "q") -> np.ndarray:
        """``q`` as a float array of shape (n,) or (N, n), or ``ValueError`` naming what is wrong."""
        return as_array(  # joint values up to 1e150 in size: a prismatic 1e308 summed to inf (issue 21)
            q,
            name,
            (self.n,),
            batch=True,
            what=f"joint values of shape ({self.n},) or (N, {self.n}) for {self.name}",
            max_magnitude=MAX_MAGNITUDE,
        )

    def q(self, name: str) -> np.ndarray:
        """A named configuration (a copy), e.g. ``arm.q("qz")``."""
        if not isinstance(name, str) or name not in self.configurations:
            got = repr(name) if isinstance(name, str) else f"a {type(name).__name__}"
            raise ValueError(f"name: expected one of {sorted(self.configurations)}, got {got}")
        return self.configurations[name].copy()

    def _check_near(self, near: Any, batch: int | None = None) -> np.ndarray | None:
        """``near`` as (n,) (or broadcast to (batch, n)), or None."""
        if near is None:
            return None
        if batch is None and type(near) is np.ndarray and near.shape == (self.n,) and near.dtype == np.float64:
            if all(math.isfinite(v) for v in near.tolist()):
                return near  # the common case, checked in plain floats
        what = f"a joint vector of shape ({self.n},)" + (f" or ({batch}, {self.n})" if batch is not None else "")
        nr = as_array(near, "near", (self.n,), batch=batch is not None, what=what)
        if batch is not None:
            if nr.ndim == 2 and nr.shape[0] != batch:
                raise ValueError(f"near: expected {what}, got an array of shape {nr.shape}")
            nr = np.broadcast_to(nr, (batch, self.n))
        return nr

    def _check_poses(self, T: Any, name: str = "T") -> np.ndarray:
        """Validated poses as (N, 4, 4) (one pose becomes N = 1)."""
        Tb = as_transform(T, name, batch=True)
        return Tb[None] if Tb.ndim == 2 else Tb

    # ---- the API -----------------------------------------------------------------------
    @abstractmethod
    def fk(self, q: Any) -> np.ndarray:
        """Pose of the end effector: (4, 4) for q (n,), (N, 4, 4) for q (N, n)."""

    @abstractmethod
    def frames(self, q: Any) -> np.ndarray:
        """Every frame of the chain (base first): (m, 4, 4) or (N, m, 4, 4)."""

    def points(self, q: Any) -> np.ndarray:
        """The polyline drawing the links: (p, 3) or (N, p, 3); by default the frames' origins."""
        return self.frames(q)[..., :3, 3]

    @abstractmethod
    def ik(self, T: Any, near: Any = None) -> IKSolutions:
        """Every configuration reaching the pose T (see :mod:`puma_course.kinematics.ik` for the policy)."""

    @abstractmethod
    def ik_batch(self, T: Any, near: Any = None) -> IKBatch:
        """Every branch for N poses T (N, 4, 4), vectorised."""

    @abstractmethod
    def parameters(self) -> dict[str, float]:
        """The robot's constant lengths (its units)."""

    # ---- shared helpers for ik ---------------------------------------------------------
    def _finish(self, sol: IKSolutions, near: np.ndarray | None, stacklevel: int = 3) -> IKSolutions:
        """Sort nearest-first when ``near`` is given and warn once at a singular pose."""
        if near is not None:
            sol = sol._sorted(near)
        if sol.singular:
            text = "; ".join(f"{k}: {sol.messages.get(k, k)}" for k in sol.singular)
            how = f" ({sol.method})" if sol.method else ""
            warnings.warn(f"{self.name} IK{how}: singular pose ({text})", SingularityWarning, stacklevel=stacklevel + 1)
        return sol

    # ---- display ------------------------------------------------------------------------
    def __repr__(self) -> str:
        params = ", ".join(f"{k}={v:g}" for k, v in self.parameters().items())
        return f"{type(self).__name__}({params})"

    def _repr_html_(self) -> str:
        unit = f" [{html.escape(self.units)}]" if self.units else ""
        rows = "".join(f"<tr><td>{html.escape(k)}</td><td>{v:g}{unit}</td></tr>" for k, v in self.parameters().items())
        joints = ", ".join(
            f"{html.escape(s)} ({'revolute' if r else 'prismatic'})"
            for s, r in zip(self.joint_symbols, self.revolute, strict=True)
        )
        configs = ", ".join(html.escape(k) for k in self.configurations)
        return (
            f"<table><caption>{html.escape(self.name, quote=False)}</caption>"
            f"<thead><tr><th>parameter</th><th>value</th></tr></thead><tbody>{rows}</tbody></table>"
            f"<p>joints: {joints}<br>named configurations: {configs or 'none'}</p>"
        )


class MountedFk:
    """A robot's forward kinematics with a base and a tool transform: ``base @ fk(q) @ tool``.

    ``fk`` is any batch-first forward kinematics (``robot.fk``). ``pad`` zero joints are appended to
    each q before calling it (the arm's first joints only); ``position_only`` keeps the position of
    the result with an identity rotation (where a point, not a frame, is meant); ``offset`` shifts the joint
    values first. It pickles, so a
    pose a student's configuration must reach can travel as data.

    >>> from puma_course.kinematics import Puma560
    >>> arm = Puma560()
    >>> shifted = MountedFk(arm.fk, base=np.diag([1.0, 1.0, 1.0, 1.0]), tool=np.eye(4))
    >>> bool(np.allclose(shifted(np.zeros(6)), arm.fk(np.zeros(6))))
    True
    >>> MountedFk(arm.fk, pad=3, position_only=True)(np.zeros((2, 3))).shape
    (2, 4, 4)

    ``offset`` is added to every q first (a joint whose zero lies elsewhere):

    >>> from puma_course.kinematics import Porter
    >>> rod = MountedFk(Porter().fk, offset=[0, 0, 0.4, 0, 0, 0])  # a rod 0.4 long at stroke 0
    >>> bool(np.allclose(rod([0, 0, 0.1, 0, 0, 0]), Porter().fk([0, 0, 0.5, 0, 0, 0])))
    True
    """

    def __init__(
        self,
        fk: Any,
        base: Any = None,
        tool: Any = None,
        pad: int = 0,
        position_only: bool = False,
        offset: Any = None,
    ) -> None:
        if not callable(fk):
            raise ValueError(f"fk: expected a forward kinematics function (robot.fk), got {type(fk).__name__}")
        self.fk = fk
        #: added to every q before ``fk``: joints whose zero lies elsewhere (a telescopic rod's fixed part)
        try:
            self.offset = None if offset is None else np.asarray(offset, dtype=float)
        except (TypeError, ValueError):
            self.offset = np.array([np.nan])
        if self.offset is not None and (self.offset.ndim != 1 or not np.all(np.isfinite(self.offset))):
            raise ValueError(f"offset: expected a finite vector of joint values, got {offset!r}")
        self.base = np.eye(4) if base is None else as_transform(base, "base")
        self.tool = np.eye(4) if tool is None else as_transform(tool, "tool")
        pad = as_count(pad, "pad", maximum=64)
        if not isinstance(position_only, (bool, np.bool_)):
            raise ValueError(f"position_only: expected True or False, got {position_only!r}")
        self.pad, self.position_only = pad, bool(position_only)

    def __call__(self, q: Any) -> np.ndarray:
        Q = as_array(q, "q", max_magnitude=MAX_MAGNITUDE)  # np.asarray(None, float) was NaN (issue 21)
        if self.offset is not None:
            Q = Q + self.offset
        if self.pad:
            Q2 = np.atleast_2d(Q)
            Q2 = np.concatenate([Q2, np.zeros((len(Q2), self.pad))], axis=1)
            T = np.asarray(self.fk(Q2))
            if self.position_only:
                out = np.tile(np.eye(4), (len(Q2), 1, 1))
                out[:, :3, 3] = T[:, :3, 3]
                T = out
            return self.base @ T @ self.tool
        T = np.asarray(self.fk(Q))
        if self.position_only:
            out = np.broadcast_to(np.eye(4), T.shape).copy()
            out[..., :3, 3] = T[..., :3, 3]
            T = out
        return self.base @ T @ self.tool

"""Craig's modified Denavit-Hartenberg convention: the link matrix, DH tables and chains.

Frame {i} is attached to link i with Z_i along joint axis i. The link matrix

    ^{i-1}T_i = Rot(X, α_{i-1}) Trans(X, a_{i-1}) Rot(Z, θ_i) Trans(Z, d_i)

maps coordinates of frame {i} into frame {i-1} (Meghdari, "the T transformation"; Craig,
eq. 3.6). Parameters carry the index of the frame they are measured in: α_{i-1}, a_{i-1}
along/about X_{i-1}; θ_i, d_i along/about Z_i. This is *not* the standard (distal) DH of Paul
or of Robotics Toolbox's ``DHRobot``; mixing the two is the commonest mistake.
"""

from __future__ import annotations

import html
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_choice, as_length, as_transform
from .ik import IKBatch, IKSolutions
from .jacobian_columns import columns_to_array, walk_columns
from .robot import Robot

__all__ = ["mdh", "Link", "DHChain"]


def exact_cos_sin(angle: float) -> tuple[float, float]:
    """cos and sin of a constant twist, exact (0, ±1) at multiples of 90° (cos(π/2) is 6e-17 in floats).

    Snapping the table's constant angles keeps the zeros of a link matrix exactly zero, so no
    result depends on how a platform rounds cos(π/2).

    >>> exact_cos_sin(-math.pi / 2)
    (0.0, -1.0)
    """
    quarter = angle / (math.pi / 2)
    k = round(quarter)
    if abs(quarter - k) < 1e-13:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[k % 4]
    return math.cos(angle), math.sin(angle)


def mdh(alpha_prev: Any, a_prev: Any, theta: Any, d: Any) -> np.ndarray:
    """Craig's link matrix ^{i-1}T_i for the parameters (α_{i-1}, a_{i-1}, θ_i, d_i).

    Arguments broadcast against each other: scalars give (4, 4), arrays of shape S give
    S + (4, 4).

        [ cθ        -sθ        0     a    ]
        [ sθ cα     cθ cα     -sα   -sα d ]
        [ sθ sα     cθ sα      cα    cα d ]
        [ 0          0         0     1    ]

    >>> np.round(mdh(0.0, 1.0, np.pi / 2, 0.5) @ [1, 0, 0, 1], 12)
    array([1. , 1. , 0.5, 1. ])
    """
    al = as_array(alpha_prev, "alpha_prev", what="an angle in radians (number or array)")
    a = as_array(a_prev, "a_prev", what="a length (number or array)", max_magnitude=MAX_MAGNITUDE)
    th = as_array(theta, "theta", what="an angle in radians (number or array)")
    dd = as_array(d, "d", what="a length (number or array)", max_magnitude=MAX_MAGNITUDE)
    try:
        shape = np.broadcast_shapes(al.shape, a.shape, th.shape, dd.shape)
    except ValueError:
        raise ValueError(
            "alpha_prev, a_prev, theta, d: expected arrays that broadcast together, got shapes "
            f"{al.shape}, {a.shape}, {th.shape}, {dd.shape}"
        ) from None
    ca, sa = np.cos(al), np.sin(al)
    ct, st = np.cos(th), np.sin(th)
    T = np.zeros(shape + (4, 4))
    T[..., 0, 0], T[..., 0, 1], T[..., 0, 3] = ct, -st, a
    T[..., 1, 0], T[..., 1, 1], T[..., 1, 2], T[..., 1, 3] = st * ca, ct * ca, -sa, -sa * dd
    T[..., 2, 0], T[..., 2, 1], T[..., 2, 2], T[..., 2, 3] = st * sa, ct * sa, ca, ca * dd
    T[..., 3, 3] = 1.0
    return T


@dataclass(frozen=True)
class Link:
    """One row of a modified-DH table.

    For a revolute joint (``kind="R"``) the joint variable is θ_i and ``theta`` is a constant
    offset added to it; for a prismatic joint (``kind="P"``) the variable is d_i and ``d`` is
    the offset.

    >>> Link(alpha_prev=-np.pi / 2, a_prev=0.0, d=0.15).kind
    'R'
    """

    alpha_prev: float
    a_prev: float
    d: float = 0.0
    theta: float = 0.0
    kind: str = "R"

    def __post_init__(self) -> None:
        for name in ("alpha_prev", "theta"):
            value = as_array(getattr(self, name), name, (), what="an angle in radians (a single number)")
            object.__setattr__(self, name, float(value))
        for name in ("a_prev", "d"):
            object.__setattr__(self, name, as_length(getattr(self, name), name))
        as_choice(self.kind, "kind", ("R", "P"))


# A frame as 12 numbers (rows x, y, z of columns 0..3), each a float or an (N,) array.
_Frame = tuple[Any, ...]


def _walk(
    twists: Sequence[tuple[float, float]],
    a: Sequence[float],
    d: Sequence[float],
    theta: Sequence[float],
    revolute: Sequence[bool],
    q: Sequence[Any],
    cos: Callable[[Any], Any],
    sin: Callable[[Any], Any],
    keep: bool,
) -> list[_Frame]:
    """Multiply Craig's link matrices column by column: the one fk kernel of every DH chain.

    Right-multiplying T by a link matrix only mixes T's columns: with u = cα T1 + sα T2,
    T0' = cθ T0 + sθ u, T1' = cθ u - sθ T0, T2' = cα T2 - sα T1, T3' = a T0 + d T2' + T3.
    Each entry of ``q`` is one joint's value: a float (one pose, plain-float arithmetic, a few
    µs) or an (N,) array (a batch, one vectorised pass per link). Twists at multiples of 90°
    (``exact_cos_sin``) skip the products by 0 and 1.
    """
    x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3 = 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0
    out: list[_Frame] = []
    if keep:
        out.append((x0, x1, x2, x3, y0, y1, y2, y3, z0, z1, z2, z3))
    for i, (ca, sa) in enumerate(twists):
        if revolute[i]:
            th, di = q[i] + theta[i], d[i]
        else:
            th, di = theta[i], q[i] + d[i]
        ct, st = cos(th), sin(th)
        if sa == 0.0:  # α = 0 or π: u = ±T1, T2' = ±T2
            ux, uy, uz = ca * x1, ca * y1, ca * z1
            x2, y2, z2 = ca * x2, ca * y2, ca * z2
        elif ca == 0.0:  # α = ±90°: u = ±T2, T2' = ∓T1
            ux, uy, uz = sa * x2, sa * y2, sa * z2
            x2, y2, z2 = -sa * x1, -sa * y1, -sa * z1
        else:
            ux, uy, uz = ca * x1 + sa * x2, ca * y1 + sa * y2, ca * z1 + sa * z2
            x2, y2, z2 = ca * x2 - sa * x1, ca * y2 - sa * y1, ca * z2 - sa * z1
        ai = a[i]
        x3, y3, z3 = x3 + ai * x0 + di * x2, y3 + ai * y0 + di * y2, z3 + ai * z0 + di * z2
        x0, y0, z0, x1, y1, z1 = (
            ct * x0 + st * ux, ct * y0 + st * uy, ct * z0 + st * uz,
            ct * ux - st * x0, ct * uy - st * y0, ct * uz - st * z0,
        )  # fmt: skip
        if keep:
            out.append((x0, x1, x2, x3, y0, y1, y2, y3, z0, z1, z2, z3))
    if not keep:
        out.append((x0, x1, x2, x3, y0, y1, y2, y3, z0, z1, z2, z3))
    return out


def frame_array(F: _Frame, batch: int | None) -> np.ndarray:
    """A 12-number frame as a 4x4 array (``batch`` None) or (N, 4, 4) from (N,) entries."""
    if batch is None:
        return np.array([F[0:4], F[4:8], F[8:12], (0.0, 0.0, 0.0, 1.0)], dtype=float)
    T = np.zeros((batch, 4, 4))
    for k, v in enumerate(F):
        T[:, k // 4, k % 4] = v
    T[:, 3, 3] = 1.0
    return T


def split_q(q: Any, n: int, check: Callable[[Any], np.ndarray]) -> tuple[list[Any], int | None]:
    """Joint values as a list of n per-joint entries: floats for one pose (a fast path that skips
    numpy for a float64 vector), (N,) arrays for a batch; and the batch size (None for one pose)."""
    if type(q) is np.ndarray and q.shape == (n,) and q.dtype == np.float64:
        values = q.tolist()
        if all(math.isfinite(v) and abs(v) <= MAX_MAGNITUDE for v in values):
            return values, None
    arr = check(q)
    if arr.ndim == 1:
        return arr.tolist(), None
    return list(arr.T), arr.shape[0]


class DHChain(Robot):
    """A serial chain described by a modified-DH table (Craig's convention).

    ``fk(q)`` gives ^0T_n (times the tool transform, if any); ``frames(q)`` every ^0T_i
    (i = 0..n). ``q`` of shape (n,) gives (4, 4); (N, n) gives (N, 4, 4), one vectorised
    pass per link, never a Python loop over the N configurations. A general chain has no
    closed-form inverse kinematics here: the course's arms (:class:`~.puma560.Puma560`,
    :class:`~.mk3.MK3`) subclass it and add theirs.

    A planar two-link arm (links of length 1 and 0.5, the second measured to the tool frame):

    >>> arm = DHChain([Link(0, 0), Link(0, 1.0), Link(0, 0.5)], name="planar")
    >>> np.round(arm.fk([np.pi / 2, -np.pi / 2, 0.0])[:3, 3], 12) + 0.0
    array([0.5, 1. , 0. ])
    """

    def __init__(
        self,
        links: Sequence[Link],
        name: str = "chain",
        units: str = "",
        configurations: Mapping[str, Any] | None = None,
        tool: Any = None,
        qlim: Any = None,
    ) -> None:
        links = tuple(links) if isinstance(links, (list, tuple)) else links
        if not isinstance(links, tuple) or not links:
            raise ValueError(f"links: expected a non-empty list of Link(alpha_prev, a_prev, d, theta), got {links!r}")
        for i, lk in enumerate(links):
            if not isinstance(lk, Link):
                raise ValueError(f"links[{i}]: expected a Link(alpha_prev, a_prev, d, theta), got {type(lk).__name__}")
        if not isinstance(name, str) or not isinstance(units, str):
            raise ValueError(f"name, units: expected strings, got {type(name).__name__} and {type(units).__name__}")
        self.links: tuple[Link, ...] = links
        self.name, self.units = name, units
        self._twists = [exact_cos_sin(lk.alpha_prev) for lk in links]
        self._a = [lk.a_prev for lk in links]
        self._d = [lk.d for lk in links]
        self._theta = [lk.theta for lk in links]
        self._rev = [lk.kind == "R" for lk in links]
        self.tool = None if tool is None else as_transform(tool, "tool")
        configs = {} if configurations is None else configurations  # `or {}` was numpy's "ambiguous" for arrays
        self._init_joints(self._rev, configs, qlim, tuple(f"θ{i + 1}" if r else f"d{i + 1}" for i, r in
                                                          enumerate(self._rev)))  # fmt: skip

    def _split(self, q: Any) -> tuple[list[Any], int | None]:
        return split_q(q, self.n, self.check_q)

    def link_matrices(self, q: Any) -> np.ndarray:
        """Every link matrix ^{i-1}T_i: shape (n, 4, 4), or (N, n, 4, 4) for a batch."""
        q = self.check_q(q)
        al = np.array([lk.alpha_prev for lk in self.links])
        a = np.array(self._a)
        theta = np.where(self._rev, np.array(self._theta) + q, self._theta)
        d = np.where(self._rev, self._d, np.array(self._d) + q)
        return mdh(np.broadcast_to(al, q.shape), np.broadcast_to(a, q.shape), theta, d)

    def _frames12(self, q: Any, keep: bool) -> tuple[list[_Frame], int | None]:
        cols, batch = self._split(q)
        cos, sin = (math.cos, math.sin) if batch is None else (np.cos, np.sin)
        return _walk(self._twists, self._a, self._d, self._theta, self._rev, cols, cos, sin, keep), batch

    def frames(self, q: Any) -> np.ndarray:
        """^0T_i for i = 0..n (plus the tool frame if one is set): (n+1, 4, 4) or (N, n+1, 4, 4)."""
        F, batch = self._frames12(q, keep=True)
        out = np.stack([frame_array(f, batch) for f in F], axis=-3)
        if self.tool is not None:
            out = np.concatenate([out, (out[..., -1, :, :] @ self.tool)[..., None, :, :]], axis=-3)
        return out

    def fk(self, q: Any) -> np.ndarray:
        """Forward kinematics ^0T_n (times the tool transform, if any): (4, 4) or (N, 4, 4).

        Equal to the product of :meth:`link_matrices`, computed without forming them.
        """
        F, batch = self._frames12(q, keep=False)
        T = frame_array(F[-1], batch)
        return T if self.tool is None else T @ self.tool

    def jacobian(self, q: Any) -> np.ndarray:
        """The geometric Jacobian [J_v; J_ω] (6, n), or (N, 6, n): see :mod:`~.jacobian`.

        >>> from puma_course import Puma560
        >>> Puma560().jacobian(np.zeros(6)).shape
        (6, 6)
        """
        F, batch = self._frames12(q, keep=True)  # q checked once here; the frames are the package's own
        return columns_to_array(walk_columns(F, self._rev), batch)

    def ik(self, T: Any, near: Any = None) -> IKSolutions:
        """Not available for a general chain (the course's arms add their closed forms)."""
        raise NotImplementedError(f"{self.name}: a general DH chain has no closed-form inverse kinematics here")

    def ik_batch(self, T: Any, near: Any = None) -> IKBatch:
        """Not available for a general chain (the course's arms add their closed forms)."""
        raise NotImplementedError(f"{self.name}: a general DH chain has no closed-form inverse kinematics here")

    def parameters(self) -> dict[str, float]:
        """The table's constants: α_{i-1} (radians), a_{i-1}, and the fixed θ_i or d_i."""
        out: dict[str, float] = {}
        for i, lk in enumerate(self.links, start=1):
            out[f"alpha{i - 1}"], out[f"a{i - 1}"] = lk.alpha_prev, lk.a_prev
            out[f"d{i}" if lk.kind == "R" else f"theta{i}"] = lk.d if lk.kind == "R" else lk.theta
        return out

    # ---- display -------------------------------------------------------
    def table(self) -> list[dict[str, Any]]:
        """The DH table as rows of plain numbers (angles in degrees for display)."""
        rows = []
        for i, lk in enumerate(self.links, start=1):
            if lk.kind == "R":
                theta: Any = f"θ{i}" + (f" {np.degrees(lk.theta):+g}°" if lk.theta else "")
                d: Any = lk.d
            else:
                theta, d = f"{np.degrees(lk.theta):g}°", f"d{i}" + (f" {lk.d:+g}" if lk.d else "")
            rows.append(
                {"i": i, "alpha_{i-1} [deg]": float(np.degrees(lk.alpha_prev)), "a_{i-1}": lk.a_prev, "theta_i": theta,
                 "d_i": d}
            )  # fmt: skip
        return rows

    def __repr__(self) -> str:
        head = f"{type(self).__name__} {self.name!r} ({self.n} joints, modified DH, lengths in {self.units or 'units'})"
        lines = [head, f"{'i':>2} {'α_{i-1} [deg]':>14} {'a_{i-1}':>10} {'θ_i':>8} {'d_i':>10}"]
        for r in self.table():
            d = r["d_i"] if isinstance(r["d_i"], str) else format(r["d_i"], "g")
            lines.append(f"{r['i']:>2} {r['alpha_{i-1} [deg]']:>14g} {r['a_{i-1}']:>10g} {r['theta_i']:>8} {d:>10}")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        unit = html.escape(self.units or "")
        cells = "".join(
            f"<tr><td>{r['i']}</td><td>{r['alpha_{i-1} [deg]']:g}</td><td>{r['a_{i-1}']:g}</td>"
            f"<td>{html.escape(str(r['theta_i']))}</td>"
            f"<td>{html.escape(r['d_i']) if isinstance(r['d_i'], str) else format(r['d_i'], 'g')}</td></tr>"
            for r in self.table()
        )
        return (
            f"<table><caption>{html.escape(self.name, quote=False)}: modified DH (Craig), lengths in {unit}</caption>"
            "<thead><tr><th>i</th><th>α<sub>i-1</sub> [deg]</th><th>a<sub>i-1</sub></th>"
            "<th>θ<sub>i</sub></th><th>d<sub>i</sub></th></tr></thead>"
            f"<tbody>{cells}</tbody></table>"
        )

"""Craig's modified Denavit-Hartenberg convention: the link matrix and chains.

Frame {i} is attached to link i with Z_i along joint axis i. The link matrix

    ^{i-1}T_i = Rot(X, α_{i-1}) Trans(X, a_{i-1}) Rot(Z, θ_i) Trans(Z, d_i)

maps coordinates of frame {i} into frame {i-1} (Meghdari, "the T
transformation"; Craig, eq. 3.6). Parameters carry the index of the frame
they are measured in: α_{i-1}, a_{i-1} along/about X_{i-1}; θ_i, d_i
along/about Z_i. This is *not* the standard (distal) DH of Paul or of
robotics-toolbox ``DHRobot``; mixing the two is the commonest mistake.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._validate import as_array

__all__ = ["mdh", "Link", "DHChain"]


def mdh(alpha_prev: Any, a_prev: Any, theta: Any, d: Any) -> np.ndarray:
    """Craig's link matrix ^{i-1}T_i for the parameters (α_{i-1}, a_{i-1}, θ_i, d_i).

    Arguments broadcast against each other: scalars give (4, 4), arrays of
    shape S give S + (4, 4).

        [ cθ        -sθ        0     a    ]
        [ sθ cα     cθ cα     -sα   -sα d ]
        [ sθ sα     cθ sα      cα    cα d ]
        [ 0          0         0     1    ]

    >>> np.round(mdh(0.0, 1.0, np.pi / 2, 0.5) @ [1, 0, 0, 1], 12)
    array([1. , 1. , 0.5, 1. ])
    """
    al = as_array(alpha_prev, "alpha_prev", what="an angle in radians (number or array)")
    a = as_array(a_prev, "a_prev", what="a length (number or array)")
    th = as_array(theta, "theta", what="an angle in radians (number or array)")
    dd = as_array(d, "d", what="a length (number or array)")
    try:
        shape = np.broadcast_shapes(al.shape, a.shape, th.shape, dd.shape)
    except ValueError:
        raise ValueError(
            "mdh: expected alpha_prev, a_prev, theta and d to broadcast together, got shapes "
            f"{al.shape}, {a.shape}, {th.shape}, {dd.shape}"
        ) from None
    return _mdh(al, a, th, dd, shape)


def _mdh(al: np.ndarray, a: np.ndarray, th: np.ndarray, d: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    ca, sa = np.cos(al), np.sin(al)
    ct, st = np.cos(th), np.sin(th)
    T = np.zeros(shape + (4, 4))
    T[..., 0, 0] = ct
    T[..., 0, 1] = -st
    T[..., 0, 3] = a
    T[..., 1, 0] = st * ca
    T[..., 1, 1] = ct * ca
    T[..., 1, 2] = -sa
    T[..., 1, 3] = -sa * d
    T[..., 2, 0] = st * sa
    T[..., 2, 1] = ct * sa
    T[..., 2, 2] = ca
    T[..., 2, 3] = ca * d
    T[..., 3, 3] = 1.0
    return T


@dataclass(frozen=True)
class Link:
    """One row of a modified-DH table.

    For a revolute joint (``kind="R"``) the joint variable is θ_i and ``theta``
    is a constant offset added to it; for a prismatic joint (``kind="P"``) the
    variable is d_i and ``d`` is the offset.

    >>> Link(alpha_prev=-np.pi / 2, a_prev=0.0, d=0.15).kind
    'R'
    """

    alpha_prev: float
    a_prev: float
    d: float = 0.0
    theta: float = 0.0
    kind: str = "R"

    def __post_init__(self) -> None:
        for name in ("alpha_prev", "a_prev", "d", "theta"):
            as_array(getattr(self, name), name, (), what="a single number")
        if self.kind not in ("R", "P"):
            raise ValueError(f"kind: expected 'R' (revolute) or 'P' (prismatic), got {self.kind!r}")


@dataclass
class DHChain:
    """A serial chain described by a modified-DH table (Craig's convention).

    ``fk(q)`` gives ^0T_n; ``frames(q)`` gives every ^0T_i (i = 0..n) for
    drawing. ``q`` of shape (n,) gives (4, 4); (N, n) gives (N, 4, 4), one array
    operation per link, never a Python loop over the N configurations.
    ``configurations`` holds named joint vectors (radians, or lengths for P).

    A planar two-link arm (links of length 1 and 0.5, the second measured to the tool frame):

    >>> arm = DHChain([Link(0, 0), Link(0, 1.0), Link(0, 0.5)], name="planar")
    >>> np.round(arm.fk([np.pi / 2, -np.pi / 2, 0.0])[:3, 3], 12) + 0.0
    array([0.5, 1. , 0. ])
    """

    links: Sequence[Link]
    name: str = "chain"
    units: str = ""
    configurations: dict[str, np.ndarray] = field(default_factory=dict)
    tool: np.ndarray | None = None

    def __post_init__(self) -> None:
        self.links = tuple(self.links)
        if not self.links:
            raise ValueError("links: expected at least one Link, got none")
        for i, lk in enumerate(self.links):
            if not isinstance(lk, Link):
                raise ValueError(f"links[{i}]: expected a Link(alpha_prev, a_prev, theta, d), got {type(lk).__name__}")
        self._alpha = np.array([lk.alpha_prev for lk in self.links], dtype=float)
        self._a = np.array([lk.a_prev for lk in self.links], dtype=float)
        self._d = np.array([lk.d for lk in self.links], dtype=float)
        self._theta = np.array([lk.theta for lk in self.links], dtype=float)
        self._revolute = np.array([lk.kind == "R" for lk in self.links])
        self.configurations = {k: self._check_q(v, f"configurations[{k!r}]") for k, v in self.configurations.items()}

    @property
    def n(self) -> int:
        """Number of joints."""
        return len(self.links)

    def _check_q(self, q: Any, name: str = "q") -> np.ndarray:
        return as_array(
            q, name, (self.n,), batch=True, what=f"joint values of shape ({self.n},) or (N, {self.n}) for {self.name}"
        )

    def link_matrices(self, q: Any) -> np.ndarray:
        """Every link matrix ^{i-1}T_i: shape (n, 4, 4), or (N, n, 4, 4) for a batch."""
        q = self._check_q(q)
        theta = np.where(self._revolute, self._theta + q, self._theta)
        d = np.where(self._revolute, self._d, self._d + q)
        shape = q.shape
        return _mdh(np.broadcast_to(self._alpha, shape), np.broadcast_to(self._a, shape), theta, d, shape)

    def _walk(self, q: Any, keep: bool) -> list[np.ndarray]:
        """Multiply the link matrices column by column (the fast path of fk and frames).

        Right-multiplying T by Craig's link matrix only mixes T's columns:
        with u = cα T1 + sα T2,
        T0' = cθ T0 + sθ u,  T1' = -sθ T0 + cθ u,  T2' = -sα T1 + cα T2,
        T3' = a T0 + d T2' + T3.
        Each step is a handful of (N, 4) array operations, so a batch of N
        configurations costs one vectorised pass per link.
        """
        q = self._check_q(q)
        batch = q.shape[:-1]
        cols = [np.broadcast_to(np.eye(4)[:, k], batch + (4,)) for k in range(4)]
        out = [np.stack(cols, axis=-1)] if keep else []
        for i in range(self.n):
            ca, sa = np.cos(self._alpha[i]), np.sin(self._alpha[i])
            if self._revolute[i]:
                th = q[..., i, None] + self._theta[i]
                d = self._d[i]
            else:
                th = self._theta[i]
                d = q[..., i, None] + self._d[i]
            ct, st = np.cos(th), np.sin(th)
            t0, t1, t2, t3 = cols
            u = ca * t1 + sa * t2
            c2 = ca * t2 - sa * t1
            cols = [ct * t0 + st * u, ct * u - st * t0, c2, self._a[i] * t0 + d * c2 + t3]
            if keep:
                out.append(np.stack(cols, axis=-1))
        if not keep:
            out.append(np.stack(cols, axis=-1))
        return out

    def frames(self, q: Any) -> np.ndarray:
        """^0T_i for i = 0..n (plus the tool frame if one is set): (n+1, 4, 4) or (N, n+1, 4, 4)."""
        out = self._walk(q, keep=True)
        if self.tool is not None:
            out.append(out[-1] @ self.tool)
        return np.stack(out, axis=-3)

    def fk(self, q: Any) -> np.ndarray:
        """Forward kinematics ^0T_n (times the tool transform, if any).

        q of shape (n,) gives (4, 4); (N, n) gives (N, 4, 4). Equal to the
        product of :meth:`link_matrices`, computed without forming them.
        """
        T = self._walk(q, keep=False)[-1]
        if self.tool is not None:
            T = T @ self.tool
        return T

    def q(self, name: str) -> np.ndarray:
        """A named configuration (a copy), e.g. ``chain.q("qz")``."""
        try:
            return self.configurations[name].copy()
        except KeyError:
            raise ValueError(f"name: expected one of {sorted(self.configurations)}, got {name!r}") from None

    # ---- display -------------------------------------------------------
    def table(self) -> list[dict[str, Any]]:
        """The DH table as rows of plain numbers (angles in degrees for display)."""
        rows = []
        for i, lk in enumerate(self.links, start=1):
            rows.append(
                {
                    "i": i,
                    "alpha_{i-1} [deg]": float(np.degrees(lk.alpha_prev)),
                    "a_{i-1}": lk.a_prev,
                    "theta_i": f"θ{i}" + (f" {np.degrees(lk.theta):+g}°" if lk.theta and lk.kind == "R" else "")
                    if lk.kind == "R"
                    else f"{np.degrees(lk.theta):g}°",
                    "d_i": f"d{i}" + (f" {lk.d:+g}" if lk.d else "") if lk.kind == "P" else lk.d,
                }
            )
        return rows

    def __repr__(self) -> str:
        head = f"DHChain {self.name!r} ({self.n} joints, modified DH, lengths in {self.units or 'units'})"
        lines = [head, f"{'i':>2} {'α_{i-1} [deg]':>14} {'a_{i-1}':>10} {'θ_i':>8} {'d_i':>10}"]
        for r in self.table():
            lines.append(
                f"{r['i']:>2} {r['alpha_{i-1} [deg]']:>14g} {r['a_{i-1}']:>10g} {r['theta_i']:>8} "
                f"{r['d_i'] if isinstance(r['d_i'], str) else format(r['d_i'], 'g'):>10}"
            )
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
            f"<table><caption>{html.escape(self.name)}: modified DH (Craig), lengths in {unit}</caption>"
            "<thead><tr><th>i</th><th>α<sub>i-1</sub> [deg]</th><th>a<sub>i-1</sub></th>"
            "<th>θ<sub>i</sub></th><th>d<sub>i</sub></th></tr></thead>"
            f"<tbody>{cells}</tbody></table>"
        )

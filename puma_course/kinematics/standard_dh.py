"""The standard (distal) Denavit-Hartenberg convention, for comparison with the course's (Craig's, modified).

:func:`standard_dh` is the *other* convention's link matrix (Denavit-Hartenberg, Paul; frame {i}
at the far end of link i), Rot(Z, θ_i) Trans(Z, d_i) Trans(X, a_i) Rot(X, α_i), and
:func:`standard_from_modified` rewrites a modified (Craig) table in it: the columns α and a move
up one row, and α_0, a_0 become a fixed base transform; :func:`standard_fk` multiplies the rows.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_choice
from .dh import Link, mdh

__all__ = ["standard_dh", "standard_from_modified", "standard_fk"]


def standard_dh(theta: Any, d: Any, a: Any, alpha: Any) -> np.ndarray:
    """The standard (distal) DH link matrix Rot(Z, θ_i) Trans(Z, d_i) Trans(X, a_i) Rot(X, α_i) (not the course's).

    Arguments broadcast as in :func:`~.dh.mdh`; scalars give (4, 4).

        [ cθ    -sθ cα     sθ sα    a cθ ]
        [ sθ     cθ cα    -cθ sα    a sθ ]
        [ 0      sα        cα       d    ]
        [ 0      0         0        1    ]

    >>> np.round(standard_dh(np.pi / 2, 0.5, 1.0, 0.0) @ [0, 0, 0, 1], 12)  # a along the turned x
    array([0. , 1. , 0.5, 1. ])
    """
    th = as_array(theta, "theta", what="an angle in radians (number or array)")
    dd = as_array(d, "d", what="a length (number or array)", max_magnitude=MAX_MAGNITUDE)
    aa = as_array(a, "a", what="a length (number or array)", max_magnitude=MAX_MAGNITUDE)
    al = as_array(alpha, "alpha", what="an angle in radians (number or array)")
    try:
        shape = np.broadcast_shapes(th.shape, dd.shape, aa.shape, al.shape)
    except ValueError:
        raise ValueError(f"theta, d, a, alpha: expected arrays that broadcast together, got shapes {th.shape}, "
                         f"{dd.shape}, {aa.shape}, {al.shape}") from None  # fmt: skip
    ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
    T = np.zeros(shape + (4, 4))
    T[..., 0, 0], T[..., 0, 1], T[..., 0, 2], T[..., 0, 3] = ct, -st * ca, st * sa, aa * ct
    T[..., 1, 0], T[..., 1, 1], T[..., 1, 2], T[..., 1, 3] = st, ct * ca, -ct * sa, aa * st
    T[..., 2, 1], T[..., 2, 2], T[..., 2, 3] = sa, ca, dd
    T[..., 3, 3] = 1.0
    return T


def standard_from_modified(links: Sequence[Link]) -> tuple[list[tuple[float, float, float, float, str]], np.ndarray]:
    """A modified (Craig) table rewritten for the standard link matrix: rows (θ_i, d_i, a_i, α_i, kind) and a base.

    Row i takes α_i and a_i from row i+1 of the modified table (the last row gets 0, 0), and the
    first row's α_0, a_0 become the fixed base transform Rot(X, α_0) Trans(X, a_0). Then
    ``base @ standard_fk(rows, q)`` is the modified chain's ^0T_n for every q, because
    Rot(X, α) Trans(X, a) = Trans(X, a) Rot(X, α) (a turn about a line and a slide along it commute).

    >>> rows, base = standard_from_modified([Link(0, 0), Link(-np.pi / 2, 0, 0.1), Link(0, 0.4)])
    >>> [(round(float(np.degrees(al))), a) for _, _, a, al, _ in rows]
    [(-90, 0.0), (0, 0.4), (0, 0.0)]
    """
    if isinstance(links, (str, bytes)) or not isinstance(links, Sequence) or len(links) == 0 or \
            not all(isinstance(lk, Link) for lk in links):  # fmt: skip
        raise ValueError(f"links: expected a non-empty list of Link rows, got {links!r}"[:200])
    rows = []
    for i, lk in enumerate(links):
        nxt = links[i + 1] if i + 1 < len(links) else Link(0.0, 0.0)
        rows.append((lk.theta, lk.d, nxt.a_prev, nxt.alpha_prev, lk.kind))
    return rows, mdh(links[0].alpha_prev, links[0].a_prev, 0.0, 0.0)


def standard_fk(rows: Sequence[Sequence[Any]], q: Any) -> np.ndarray:
    """The product of standard link matrices for rows (θ_i, d_i, a_i, α_i, kind) at joint values q (n,): (4, 4).

    A revolute row adds q_i to θ_i, a prismatic one to d_i.

    >>> np.round(standard_fk([(0.0, 0.0, 1.0, 0.0, "R"), (0.0, 0.0, 1.0, 0.0, "R")], [np.pi / 2, 0.0])[:3, 3], 12)
    array([0., 2., 0.])
    """
    if isinstance(rows, (str, bytes)) or not isinstance(rows, Sequence) or len(rows) == 0 or \
            any(not isinstance(r, Sequence) or len(r) != 5 for r in rows):  # fmt: skip
        raise ValueError("rows: expected a non-empty list of rows (theta, d, a, alpha, kind)")
    table = as_array([r[:4] for r in rows], "rows", (None, 4), what="rows of four numbers and a kind 'R' or 'P'",
                     max_magnitude=MAX_MAGNITUDE)  # fmt: skip
    kinds = [as_choice(r[4], "rows", ("R", "P")) for r in rows]
    n = len(rows)
    qq = as_array(q, "q", (n,), what=f"{n} joint values (radians or lengths)", max_magnitude=MAX_MAGNITUDE)
    T = np.eye(4)
    for (th, d, a, al), kind, qi in zip(table.tolist(), kinds, qq.tolist(), strict=True):
        T = T @ (standard_dh(th + qi, d, a, al) if kind == "R" else standard_dh(th, d + qi, a, al))
    return T

"""The two arms of Meghdari's lecture as modified-DH chains: PUMA-560 and MK3.

* :func:`puma560`: Unimation PUMA-560 (6R), lengths in metres, the lecture's
  table (Craig's frame assignment, frame {0} coincident with {1} at θ1 = 0).
* :func:`mk3`: Yaskawa Motoman MK3 (5R), lengths in millimetres.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._validate import as_array
from .dh import DHChain, Link

__all__ = ["puma560", "mk3", "PUMA560_DEFAULTS", "MK3_DEFAULTS"]

PUMA560_DEFAULTS = {"a2": 0.4318, "a3": 0.0203, "d3": 0.15005, "d4": 0.4318}
MK3_DEFAULTS = {"d1": 360.0, "a1": 135.0, "a2": 250.0, "a3": 215.0, "d5": 100.0}

_H = np.pi / 2


def puma560(
    a2: float = PUMA560_DEFAULTS["a2"],
    a3: float = PUMA560_DEFAULTS["a3"],
    d3: float = PUMA560_DEFAULTS["d3"],
    d4: float = PUMA560_DEFAULTS["d4"],
) -> DHChain:
    """The PUMA-560 of the lecture's table (modified DH, metres).

    ======  =========  =======  =====
    i       α_{i-1}    a_{i-1}  d_i
    ======  =========  =======  =====
    1       0          0        0
    2       -90°       0        0
    3       0          a2       d3
    4       -90°       a3       d4
    5       90°        0        0
    6       -90°       0        0
    ======  =========  =======  =====

    Named configurations (``chain.q(name)``): ``qz`` all zeros (upper arm
    horizontal, forearm hanging down); ``qr`` ready, arm straight up;
    ``qs`` stretched, arm horizontal along x; ``qn`` nominal, elbow bent with
    the wrist pointing down.

    >>> T = puma560().fk(np.zeros(6))
    >>> np.round(T[:3, 3], 5)  # (a2 + a3, d3, -d4)
    array([ 0.4521 ,  0.15005, -0.4318 ])
    """
    lengths = {
        name: float(as_array(v, name, (), what="a length in metres (a number)"))
        for name, v in (("a2", a2), ("a3", a3), ("d3", d3), ("d4", d4))
    }
    links = [
        Link(0.0, 0.0, 0.0),
        Link(-_H, 0.0, 0.0),
        Link(0.0, lengths["a2"], lengths["d3"]),
        Link(-_H, lengths["a3"], lengths["d4"]),
        Link(_H, 0.0, 0.0),
        Link(-_H, 0.0, 0.0),
    ]
    configs = {
        "qz": np.zeros(6),
        "qr": np.array([0.0, -_H, -_H, 0.0, 0.0, 0.0]),
        "qs": np.array([0.0, 0.0, -_H, 0.0, 0.0, 0.0]),
        "qn": np.array([0.0, -np.pi / 4, -np.pi / 4, 0.0, np.pi / 4, 0.0]),
    }
    return PumaChain(links=links, name="PUMA-560", units="m", configurations=configs)


class PumaChain(DHChain):
    """A PUMA-560 chain with closed-form inverse kinematics (lecture 09, :mod:`puma_course.puma_ik`)."""

    @property
    def lengths(self) -> dict[str, float]:
        """The four lengths of the table: a2, a3, d3, d4 (the chain's units)."""
        return {"a2": self._a[2], "a3": self._a[3], "d3": self._d[2], "d4": self._d[3]}

    def ik(self, T: Any, near: Any | None = None, *, tol: float = 1e-7):
        """Every joint vector reaching the pose T (closed form, Craig §4.7): an ``IKResult``.

        Up to eight solutions labelled shoulder left/right, elbow up/down, wrist
        noflip/flip; ``near`` sorts them by wrapped joint distance (nearest
        first). Unreachable T raises ``ValueError`` with the reason; a
        singular pose warns (``SingularityWarning``). See :func:`puma_ik.ik`.

        >>> arm = puma560()
        >>> q = arm.q("qn")
        >>> sol = arm.ik(arm.fk(q), near=q)
        >>> len(sol), bool(np.allclose(sol[0], q))
        (8, True)
        """
        from .puma_ik import ik

        lengths = {k: float(v) for k, v in self.lengths.items()}
        return ik(T, **lengths, near=near, tol=tol, stacklevel=3)

    def ik_batch(self, T: Any, near: Any | None = None, *, tol: float = 1e-7):
        """All eight branches for N poses (N, 4, 4), vectorised: an ``IKBatch`` (q (N, 8, 6), valid (N, 8))."""
        from .puma_ik import ik_batch

        return ik_batch(
            T, float(self._a[2]), float(self._a[3]), float(self._d[2]), float(self._d[3]), near=near, tol=tol
        )


def mk3(
    d1: float = MK3_DEFAULTS["d1"],
    a1: float = MK3_DEFAULTS["a1"],
    a2: float = MK3_DEFAULTS["a2"],
    a3: float = MK3_DEFAULTS["a3"],
    d5: float = MK3_DEFAULTS["d5"],
) -> DHChain:
    """The Yaskawa Motoman MK3 (5R) of the lecture's table (modified DH, millimetres).

    ======  =========  =======  =====
    i       α_{i-1}    a_{i-1}  d_i
    ======  =========  =======  =====
    1       0          0        d1
    2       90°        a1       0
    3       0          a2       0
    4       0          a3       0
    5       90°        0        d5
    ======  =========  =======  =====

    Named configurations: ``qz`` all zeros (both arm links horizontal, the
    tool axis z5 pointing straight down); ``qr`` ready (upper arm vertical,
    forearm horizontal, tool pointing down).

    >>> np.round(mk3().fk(np.zeros(5))[:3, 3], 6) + 0.0  # (a1 + a2 + a3, 0, d1 - d5)
    array([600.,   0., 260.])
    """
    lengths = {
        name: float(as_array(v, name, (), what="a length in millimetres (a number)"))
        for name, v in (("d1", d1), ("a1", a1), ("a2", a2), ("a3", a3), ("d5", d5))
    }
    links = [
        Link(0.0, 0.0, lengths["d1"]),
        Link(_H, lengths["a1"], 0.0),
        Link(0.0, lengths["a2"], 0.0),
        Link(0.0, lengths["a3"], 0.0),
        Link(_H, 0.0, lengths["d5"]),
    ]
    configs = {
        "qz": np.zeros(5),
        "qr": np.array([0.0, _H, -_H, 0.0, 0.0]),
    }
    return DHChain(links=links, name="Motoman MK3", units="mm", configurations=configs)

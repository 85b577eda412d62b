"""The PUMA-560's singularities swept joint by joint (lecture 09 §8): how far apart the branches a
singularity decides are, and the figure of the three sweeps. Split from :mod:`.ik_figures`, which
re-exports every name."""

from __future__ import annotations

import math
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from .._validate import as_array, as_count, as_length
from ..kinematics.ik import nearest_index
from ..kinematics.puma560 import BRANCH_LABELS, Puma560
from ..transforms import wrap_angle

__all__ = ["DECIDED_JOINT", "SWEPT_JOINT", "branch_gaps", "plot_singularity_sweeps", "singularity_sweep"]

#: The joint each singularity's ± decides (0-based index into q): θ1 shoulder, θ3 elbow, θ5 wrist.
DECIDED_JOINT = {"shoulder": 0, "elbow": 2, "wrist": 4}
#: The joint :func:`singularity_sweep` turns to cross each singularity: θ2, θ3, θ5.
SWEPT_JOINT = {"shoulder": 1, "elbow": 2, "wrist": 4}
#: Which branch meets which: XOR of the index in BRANCH_LABELS (4 shoulder, 2 elbow, 1 wrist bit).
#: At the shoulder singularity left/up meets right/down: "up" is measured along the reach X, which turns over.
_PARTNER = {"shoulder": 6, "elbow": 2, "wrist": 1}


def as_puma(arm: Any) -> Puma560:
    """``arm`` if it is a :class:`Puma560`, else ``ValueError`` naming it (the figures here and in
    :mod:`.ik_figures` draw that arm only)."""
    if not isinstance(arm, Puma560):
        raise ValueError(f"arm: expected a Puma560(), got {type(arm).__name__}")
    return arm


def branch_gaps(arm: Puma560, Q: Any) -> tuple[list[str], dict[str, np.ndarray]]:
    """The branch of each joint vector in ``Q`` (N, 6) and, per singularity, how far it is from the branch
    it merges with there: the wrapped difference (radians) of the joint that singularity's ± decides.

    The partners: flip ↔ noflip at the wrist (θ5), up ↔ down at the elbow (θ3), and at the shoulder
    left/up ↔ right/down (θ1; "up" is measured along the reach, which turns over with the shoulder).
    A gap is 0 where the pose is singular for that word (the two solutions coincide).

    >>> labels, gaps = branch_gaps(Puma560(), np.radians([[30, -50, 20, 40, 60, -30]]))
    >>> labels, round(float(np.degrees(gaps["wrist"][0])), 6)  # noflip and flip: θ5 and -θ5
    (['left/up/noflip'], 120.0)
    """
    arm = as_puma(arm)
    Qc = np.atleast_2d(arm.check_q(Q))
    b = arm.ik_batch(arm.fk(Qc), near=Qc)
    if not b.reachable.all():  # fk of a joint vector is always reachable; only a bad input gets here
        raise ValueError("Q: expected joint vectors whose poses the arm reaches")
    rows = np.arange(len(Qc))
    own = nearest_index(b.q, Qc, arm.revolute, b.valid)
    gaps = {}
    for word, j in DECIDED_JOINT.items():
        partner = own ^ _PARTNER[word]
        # a partner marked invalid is a duplicate: its row holds the values of the solution it merged into
        gaps[word] = np.abs(wrap_angle(b.q[rows, own, j] - b.q[rows, partner, j]))
    return [BRANCH_LABELS[k] for k in own], gaps


def _factor_zeros(arm: Puma560, q0: np.ndarray, word: str) -> np.ndarray:
    """Values of the swept joint in (-π, π] where the word's factor of det J vanishes, the others at q0. For the
    elbow only the stretched arm: folded, the wrist centre comes within |a2 - sqrt(a3² + d4²)| (0.5 mm) of
    joint 2's axis, the shoulder factor vanishes nearly at once and det J only touches 0."""
    L = arm.lengths
    if word == "elbow":  # a3 s3 + d4 c3 = 0, the arm stretched
        return np.array([-math.atan2(L["d4"], L["a3"])])
    if word == "shoulder":  # a2 c2 + a3 c23 - d4 s23 = c2 vx - s2 vy = 0
        c3, s3 = math.cos(q0[2]), math.sin(q0[2])
        base = math.atan2(L["a2"] + L["a3"] * c3 - L["d4"] * s3, L["a3"] * s3 + L["d4"] * c3)
    else:  # s5 = 0
        base = 0.0  # fmt: skip
    return np.sort(wrap_angle(np.array([base, base + math.pi])))


def singularity_sweep(arm: Puma560, q0: Any, word: str, *, half_width: float = math.radians(60),
                      n: int = 241) -> dict[str, Any]:  # fmt: skip
    """Turn the joint :data:`SWEPT_JOINT` [word] by ± ``half_width`` (radians) through a zero of the word's factor
    of det J (the one nearest its value in ``q0``; for the elbow the stretched arm), the other joints at ``q0``:
    det J, the gap of :func:`branch_gaps` and the branch labels along the way.

    Returns ``{"joint", "zero", "x", "det", "gap", "labels"}`` (angles in radians, det J in m³).

    >>> s = singularity_sweep(Puma560(), np.radians([30, -50, 20, 40, 60, -30]), "wrist", n=5)
    >>> np.degrees(s["x"]).round(1).tolist(), float(s["zero"]), s["labels"][0], s["labels"][-1]
    ([-60.0, -30.0, 0.0, 30.0, 60.0], 0.0, 'left/up/flip', 'left/up/noflip')
    """
    arm = as_puma(arm)
    if not isinstance(word, str) or word not in DECIDED_JOINT:
        raise ValueError(f"word: expected one of 'shoulder', 'elbow', 'wrist', got {word!r}")
    n = as_count(n, "n", minimum=3)
    half_width = as_length(half_width, "half_width", positive=True)
    q0 = as_array(q0, "q0", (6,))
    j = SWEPT_JOINT[word]
    zeros = _factor_zeros(arm, q0, word)
    zero = float(zeros[np.argmin(np.abs(wrap_angle(zeros - q0[j])))])
    x = zero + np.linspace(-half_width, half_width, n)
    Q = np.tile(q0, (n, 1))
    Q[:, j] = x
    labels, gaps = branch_gaps(arm, Q)
    det = np.linalg.det(arm.jacobian(Q))
    return {"joint": j, "zero": zero, "x": x, "det": det, "gap": gaps[word], "labels": labels}


def plot_singularity_sweeps(arm: Puma560, q0: Any, *, half_width: float = math.radians(60), n: int = 241) -> Figure:
    """Three columns (shoulder, elbow, wrist): det J (top) and the gap to the merging branch (bottom) while one
    joint turns through the singularity (:func:`singularity_sweep`); a dotted line at the zero of the
    factor, the arm's branch word shaded.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig = plot_singularity_sweeps(Puma560(), np.radians([30, -50, 20, 40, 60, -30]), n=31)
    >>> [ax.get_xlabel() for ax in fig.axes[3:]]
    ['θ2 [deg]', 'θ3 [deg]', 'θ5 [deg]']
    >>> plt.close(fig)
    """
    arm = as_puma(arm)
    fig, axes = plt.subplots(2, 3, figsize=(11, 5.6), sharex="col")
    words = {"shoulder": ("left", "right"), "elbow": ("up", "down"), "wrist": ("noflip", "flip")}
    for c, (word, (a, b)) in enumerate(words.items()):
        s = singularity_sweep(arm, q0, word, half_width=half_width, n=n)
        xd = np.degrees(s["x"])
        part = 0 if word == "shoulder" else 1 if word == "elbow" else 2
        first = np.array([lab.split("/")[part] == a for lab in s["labels"]])
        top, bottom = axes[0, c], axes[1, c]
        for ax in (top, bottom):
            for where, name, col in ((first, a, "tab:blue"), (~first, b, "tab:orange")):
                ax.fill_between(xd, 0, 1, where=where, transform=ax.get_xaxis_transform(), color=col, alpha=0.1, lw=0,
                                label=f"the arm is '{name}'")  # fmt: skip
            ax.axvline(math.degrees(s["zero"]), color="k", ls=":", lw=1.2)
        top.plot(xd, s["det"], color="k", lw=1.8)
        top.axhline(0, color="0.6", lw=0.8)
        bottom.plot(xd, np.degrees(s["gap"]), color="tab:red", lw=1.8)
        top.set_title(f"{word}: turn θ{s['joint'] + 1}")
        top.legend(loc="upper center", bbox_to_anchor=(0.5, -0.04), ncols=2, fontsize=9, frameon=False,
                   handlelength=1.0, columnspacing=0.8)  # fmt: skip
        bottom.set_xlabel(f"θ{s['joint'] + 1} [deg]")
        bottom.xaxis.set_major_locator(plt.MultipleLocator(30))
        bottom.set_ylim(bottom=0)
    axes[0, 0].set_ylabel("det J [m³]")
    axes[1, 0].set_ylabel("gap to the merging\nbranch [deg]")
    return fig


# ------------------------------------------------------------------------------------------------ workspaces

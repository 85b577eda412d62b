"""Draw the mechanisms of the exercises' frame-assignment questions, with ``puma_course.viz.draw_robot``.

    python figures/make_figures.py [OUTDIR]      (default: the folder of this script)

writes ``rrp_arm.png`` (exercise 2), ``puma_pedestal.png`` (3), ``mk3_rail.png`` (4) and
``porter_chain.png`` (5). Each shows the mechanism in two configurations with its base frame {0}, its
tool frame, and every joint axis as an arrow in the joint's positive sense (right-hand rule for a
turning joint, the direction of motion for a sliding one). The tool frames are those of the question
bank's references (the course's ``bank/_reference/``), so a picture shows what is graded; the
intermediate frames are not drawn, since choosing them is the question. Run it after changing a
mechanism in the bank, and commit the pictures with the solutions.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from puma_course import MK3, Porter, Puma560  # noqa: E402
from puma_course.grading import load_bank  # noqa: E402

load_bank(Path(__file__).resolve().parents[1])  # the course's question bank, imported as puma_course_bank
from puma_course.kinematics import Robot  # noqa: E402
from puma_course.transforms import rotz, transl, troty, trotz  # noqa: E402
from puma_course.viz import draw_robot, set_equal  # noqa: E402
from puma_course_bank._reference import chains, porter_chain  # noqa: E402

FIGURES = ("rrp_arm", "puma_pedestal", "mk3_rail", "porter_chain")
Axis = tuple[np.ndarray, np.ndarray, str]  # a point on the axis, its positive direction, its label


class Drawing(Robot):
    """A mechanism for :func:`draw_robot`: its links ``points(q)`` and two frames, the base {0} and the tool."""

    def __init__(self, name: str, revolute: list[bool], tool: Callable[[np.ndarray], np.ndarray],
                 points: Callable[[np.ndarray], np.ndarray]) -> None:  # fmt: skip
        self.name, self._tool, self._points = name, tool, points
        self._init_joints(revolute, {}, [(-1e4, 1e4)] * len(revolute))

    def fk(self, q: Any) -> np.ndarray:
        return self._tool(np.asarray(q, dtype=float))

    def frames(self, q: Any) -> np.ndarray:
        return np.stack([np.eye(4), self.fk(q)])

    def points(self, q: Any) -> np.ndarray:
        return self._points(np.asarray(q, dtype=float))

    def ik(self, T: Any, near: Any = None) -> Any:
        raise NotImplementedError

    def ik_batch(self, T: Any, near: Any = None) -> Any:
        raise NotImplementedError

    def parameters(self) -> dict[str, float]:
        return {}


def panel(ax: Any, robot: Drawing, q: np.ndarray, axes: list[Axis], dims: list[tuple[Any, Any, str]],
          title: str, length: float, tool: str = "{T}") -> None:  # fmt: skip
    """One configuration: links, base and tool triads, joint arrows, dimension labels."""
    draw_robot(ax, robot, q, triads="all", labels=["{0}", tool], length=0.8 * length, lw=4, alpha=0.9)
    for p, u, label in axes:
        u = np.asarray(u, dtype=float) / np.linalg.norm(u)
        ax.quiver(*p, *(1.3 * length * u), color="tab:purple", lw=2.5, arrow_length_ratio=0.3)
        ax.text(*(p + 1.5 * length * u), label, color="tab:purple", fontsize=11, fontweight="bold")
    for a, b, label in dims:
        m = (np.asarray(a, dtype=float) + np.asarray(b, dtype=float)) / 2
        ax.text(*m, f" {label}", color="0.25", fontsize=10, style="italic")
    pts = np.vstack([robot.points(q), robot.fk(q)[:3, 3], np.zeros(3)])
    set_equal(ax, pts, margin=0.25 * length / max(1e-9, float(np.max(np.ptp(pts, axis=0)))))
    ax.set(xlabel="x", ylabel="y", zlabel="z")
    ax.locator_params(nbins=4)
    ax.set_title(title, fontsize=10)


def figure(path: Path, robot: Drawing, cases: list[tuple[np.ndarray, str]], axes: Callable[[np.ndarray], list[Axis]],
           dims: Callable[[np.ndarray], list[tuple[Any, Any, str]]], length: float, view: tuple[float, float],
           tool: str = "{T}") -> None:  # fmt: skip
    fig = plt.figure(figsize=(11, 5.4), dpi=100)
    for k, (q, title) in enumerate(cases):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        panel(ax, robot, q, axes(q), dims(q), title, length, tool)
        ax.view_init(*view)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


# ------------------------------------------------------------------------------ the RRP arm (exercise 2)
def rrp(out: Path) -> None:
    h, d2 = 0.8, 0.2

    def pts(q: np.ndarray) -> np.ndarray:
        S = np.array([0.0, 0.0, h])
        O = S + d2 * (rotz(q[0]) @ [0.0, 1.0, 0.0])
        return np.array([np.zeros(3), S, O, chains.rrp_fk(q, h, d2)[:3, 3]])

    def axes(q: np.ndarray) -> list[Axis]:
        P, T = pts(q), chains.rrp_fk(q, h, d2)
        return [(P[1], np.array([0.0, 0.0, 1.0]), "q1"), (P[1], rotz(q[0]) @ [0.0, -1.0, 0.0], "q2"),
                ((P[2] + P[3]) / 2 + 0.06 * T[:3, 0], T[:3, 2], "q3")]  # fmt: skip

    def dims(q: np.ndarray) -> list[tuple[Any, Any, str]]:
        P = pts(q)
        return [(P[0], P[1], "h"), (P[1], P[2], "d2")]

    robot = Drawing("RRP arm", [True, True, False], lambda q: chains.rrp_fk(q, h, d2), pts)
    cases = [(np.array([0.0, 0.0, 0.6]), "q1 = q2 = 0, reach q3 = 0.6"),
             (np.array([np.radians(40), np.radians(30), 0.9]), "q = (40°, 30°, 0.9)")]  # fmt: skip
    figure(out / "rrp_arm.png", robot, cases, axes, dims, 0.16, (22, -60))


# ------------------------------------------------------------------------------ the PUMA-560 on a pedestal (exercise 3)
def puma(out: Path) -> None:
    L, h, d6 = (0.4318, 0.0203, 0.15005, 0.4318), 0.6604, 0.1
    arm, up = Puma560(*L), transl([0.0, 0.0, h])

    def moved(P: np.ndarray) -> np.ndarray:
        return P + [0.0, 0.0, h]

    def pts(q: np.ndarray) -> np.ndarray:
        P = moved(arm.points(q + chains.PUMA_ZERO)[1:])  # base origin, offset d3, elbow, step a3, wrist centre
        return np.vstack([np.zeros(3), P, chains.puma_pedestal_fk(q, *L, h, d6)[:3, 3]])

    def axes(q: np.ndarray) -> list[Axis]:
        F, P = up @ arm.frames(q + chains.PUMA_ZERO), pts(q)
        at = [P[1], P[2], P[3], P[4], P[5], P[6]]  # q4 from the forearm's foot, q6 at the tool's tip
        return [(at[i], F[i + 1, :3, 2], f"q{i + 1}") for i in range(6)]

    def dims(q: np.ndarray) -> list[tuple[Any, Any, str]]:
        P = pts(q)
        return [(P[0], P[1], "h"), (P[1], P[2], "d3"), (P[2], P[3], "a2"), (P[4], P[5], "d4"), (P[5], P[6], "d6")]

    robot = Drawing("PUMA-560", [True] * 6, lambda q: chains.puma_pedestal_fk(q, *L, h, d6), pts)
    cases = [(np.zeros(6), "q = 0: the arm straight up"),
             (np.radians([30.0, 40.0, -50.0, 20.0, 40.0, 0.0]), "q = (30°, 40°, -50°, 20°, 40°, 0)")]  # fmt: skip
    figure(out / "puma_pedestal.png", robot, cases, axes, dims, 0.14, (12, -35), tool="{6}")


# ------------------------------------------------------------------------------ the MK3 on a rail (exercise 4)
def mk3(out: Path) -> None:
    L, c = (360.0, 135.0, 250.0, 215.0, 100.0), 450.0
    robot_mk3 = MK3(*L)

    def base(q: np.ndarray) -> np.ndarray:
        return transl([0.0, q[0], c])

    def pts(q: np.ndarray) -> np.ndarray:
        F = base(q) @ robot_mk3.frames(q[1:])
        return np.vstack([[0.0, -450.0, 0.0], [0.0, 450.0, 0.0], [0.0, q[0], 0.0], F[:, :3, 3]])

    def axes(q: np.ndarray) -> list[Axis]:
        F = base(q) @ robot_mk3.frames(q[1:])
        out_ = [(np.array([0.0, q[0] + 150.0, 0.0]), np.array([0.0, 1.0, 0.0]), "q1")]
        at = [F[1, :3, 3], F[2, :3, 3], F[3, :3, 3], F[4, :3, 3], F[5, :3, 3] + 40.0 * F[5, :3, 2]]
        return out_ + [(at[i - 1], F[i, :3, 2], f"q{i + 1}") for i in range(1, 6)]

    def dims(q: np.ndarray) -> list[tuple[Any, Any, str]]:
        P = pts(q)
        return [
            (P[2], P[3], "c"),
            (P[3], P[4], "d1"),
            (P[4], P[5], "a1"),
            (P[5], P[6], "a2"),
            (P[6], P[7], "a3"),
            (P[7], P[8], "d5"),
        ]

    robot = Drawing("MK3 on a rail", [False] + [True] * 5, lambda q: chains.mk3_rail_fk(q, c, *L), pts)
    cases = [(np.zeros(6), "q = 0"), (np.array([300.0, *np.radians([40.0, 30.0, -50.0, 30.0, 60.0])]),
                                       "q = (300 mm, 40°, 30°, -50°, 30°, 60°)")]  # fmt: skip
    figure(out / "mk3_rail.png", robot, cases, axes, dims, 75.0, (15, -30), tool="{6}")


# ------------------------------------------------------------------------------ Porter's chain (exercise 5)
def porter(out: Path) -> None:
    L = (1.0, 0.5, 0.3)
    arm = Porter(*L)

    def axes(q: np.ndarray) -> list[Axis]:
        P, T = arm.points(q), arm.fk(q)
        R1 = trotz(q[0])[:3, :3]
        R2 = R1 @ troty(q[1])[:3, :3]
        R3 = R2 @ troty(q[3])[:3, :3]
        return [(np.array([0.0, 0.0, 0.3]), np.array([0.0, 0.0, 1.0]), "α1"), (P[2], R1[:, 1], "α2"),
                ((P[2] + P[3]) / 2, R2[:, 0], "q2"), (P[3], R1[:, 1], "α3"), (P[3], R3[:, 2], "α4"),
                (P[5], T[:3, 0], "α5")]  # fmt: skip

    def dims(q: np.ndarray) -> list[tuple[Any, Any, str]]:
        P = arm.points(q)
        return [(P[0], P[2], "l1"), (P[3], P[4], "l3"), (P[4], P[5], "l4")]

    robot = Drawing("Porter's chain", list(arm.revolute), lambda q: porter_chain.porter_tool_fk(q, *L), arm.points)
    cases = [(np.array([0.0, 0.0, 0.8, 0.0, 0.0, 0.0]), "q = (0, 0, 0.8, 0, 0, 0)"),
             (np.array([np.radians(40), np.radians(-20), 1.0, *np.radians([50.0, 60.0, 30.0])]),
              "q = (40°, -20°, 1.0, 50°, 60°, 30°)")]  # fmt: skip
    figure(out / "porter_chain.png", robot, cases, axes, dims, 0.2, (20, -60))


def main(argv: list[str]) -> None:
    out = Path(argv[0]) if argv else Path(__file__).resolve().parent
    out.mkdir(parents=True, exist_ok=True)
    for make in (rrp, puma, mk3, porter):
        make(out)
    print(f"wrote {', '.join(f'{name}.png' for name in FIGURES)} to {out}")


if __name__ == "__main__":
    main(sys.argv[1:])

"""Issue 25: the lecture figures whose own cells letter a triad (x, y, z or f1, f2, f3) keep the letters apart.

Each lecture's code is run here, in this process, up to the figure's cell (its magics dropped, ``plt.show``
kept from closing the figure); then every text of every panel is measured on the drawn figure: no two
overlap (letters, frame names, the DH labels), each lies inside the figure, and each panel carries its letters.
The figures the package draws alone (the frame walk, the wrist, Porter's panels) are tested in their modules' tests.
"""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib.pyplot as plt
import nbformat
import numpy as np
import pytest

from puma_course.viz.labels import overlapping_labels

NOTEBOOKS = Path(__file__).resolve().parents[2] / "notebooks"
# lecture, the figure cell's first line, the letters each panel carries
FIGURES = [
    ("02_dh_frame_attachment", "p4 = dict(alpha_prev=", ["x", "y", "z"]),
    ("03_puma560_forward_kinematics", 'names = ["qz", "qr", "qs", "qn"]', ["x", "y", "z"] * 2),
    ("08_three_step_wrist_frame", "target_pose = np.eye(4)", ["$f_1$", "$f_2$", "$f_3$"]),
    ("09_puma560_inverse_kinematics", "ring = np.linspace(0, 2 * np.pi, 100)", ["x", "y", "z"]),
]


def _figure(name: str, first_line: str):
    nb = nbformat.read(NOTEBOOKS / f"{name}.ipynb", as_version=4)
    code = [c.source for c in nb.cells if c.cell_type == "code"]
    last = next(i for i, src in enumerate(code) if first_line in src)
    shown = []
    space = {"__name__": "__lecture__"}
    show, cwd, printing = plt.show, os.getcwd(), np.get_printoptions()
    plt.show = lambda *a, **k: shown.append(plt.gcf())  # type: ignore[assignment]
    try:
        os.chdir(NOTEBOOKS)
        for src in code[: last + 1]:
            if "_panel(" in src or "RobotViewer(" in src or "animate_robot(" in src:
                continue  # widgets and animations: nothing the figure needs
            exec(compile("\n".join(ln for ln in src.splitlines() if not ln.lstrip().startswith("%")), name, "exec"),
                 space)  # fmt: skip
    finally:  # the lectures set numpy's print options: a doctest later in this worker must not see them
        plt.show = show  # type: ignore[assignment]
        os.chdir(cwd)
        np.set_printoptions(**printing)
    return shown[-1]


@pytest.mark.parametrize(("name", "first_line", "letters"), FIGURES)
def test_lettered_triads_in_the_lectures_keep_apart_and_inside(name, first_line, letters):
    fig = _figure(name, first_line)
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    for ax in fig.axes:
        texts = [t for t in ax.texts if t.get_text()]
        assert sorted(t.get_text() for t in texts if t.get_text() in letters) == sorted(letters)
        assert overlapping_labels(texts) == []
        for t in texts:
            b = t.get_window_extent(r)
            assert fig.bbox.contains(b.x0, b.y0) and fig.bbox.contains(b.x1, b.y1), t.get_text()

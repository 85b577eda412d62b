"""The student edition on a real JupyterHub: two students in Chromium, an instructor's update through nbgitpuller.

One test, in order, as a class would live it (tests/hub/hubctl.py starts everything on 127.0.0.1):

1. the instructor's edition (``puma-course edition``, or its stand-in) is a git repository on a local
   git server; the single-user environment is built from its ``binder/requirements.txt`` (the image);
2. two students (system users made for the test) log in with a password, open the nbgitpuller link,
   land on START_HERE in JupyterLab, run lecture 03 (its 3-D panel draws: a WebGL canvas with a
   picture in it), write exercise 3's first answer and run its self-check (it says passed), and save;
3. the instructor changes a lecture's text and an exercise's text, commits and pushes;
4. both open the link again: the change is in their notebooks, and so is their own answer.

All along: every request the browser makes goes to 127.0.0.1 (nothing from a CDN), the course
package the kernels import is the image's (outside the home folder, not writable by the student).
Screenshots: tests/artifacts/hub_*.png.
"""

from __future__ import annotations

import io
import json
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

import pytest

from puma_course.hub import nbgitpuller_link

from ..browser.lab import VIEWER_STATE, browser, run_all, viewers, wait_idle
from . import hubctl
from .hubctl import REPO_NAME, GitServer, Hub

pytestmark = [pytest.mark.hub, pytest.mark.browser]

ARTIFACTS = Path(__file__).resolve().parents[1] / "artifacts"
STUDENTS = ["puma-hub-s1", "puma-hub-s2"]
LECTURE = "notebooks/03_puma560_forward_kinematics.ipynb"
EXERCISE = "exercises/ex03_puma_fk.ipynb"
LECTURE_NOTE = "Instructor's note, week 5: the wrist axes 4, 5 and 6 meet in one point."
EXERCISE_NOTE = "Hint added in week 5: start from T = np.eye(4) and multiply on the right."
ANSWER = """def chain_fk(table, q, k=0):
    # the answer of {user}: one link matrix per row after frame k, multiplied on the right
    T = np.eye(4)
    for (alpha, a, theta, d, sigma), qi in zip(np.asarray(table, dtype=float)[k:], np.asarray(q, dtype=float)[k:]):
        T = T @ (mdh(alpha, a, theta, d + qi) if sigma > 0.5 else mdh(alpha, a, theta + qi, d))
    return T"""


@pytest.fixture(scope="module")
def classroom() -> Iterator[dict[str, Any]]:
    """The instructor's edition on a git server, the image's environment, two students, the hub."""
    tmp = hubctl._open_tmp("puma-hub-test-")
    edition = hubctl.make_edition(tmp / "edition")
    env = hubctl.single_user_env(edition)
    users = hubctl.make_users(STUDENTS)
    git = hub = None
    try:
        git = GitServer(edition, hubctl.ports()[3])
        hub = Hub(users, env)
        yield {"edition": edition, "env": env, "git": git, "hub": hub}
    finally:
        if hub is not None:
            hub.stop()
            (ARTIFACTS / "hub.log").parent.mkdir(exist_ok=True)
            (ARTIFACTS / "hub.log").write_text(hub.hub_log(), encoding="utf-8")
            hub.cleanup()
        if git is not None:
            git.stop()
        hubctl.delete_users(users)
        import shutil

        shutil.rmtree(tmp, ignore_errors=True)


# ---- what a student does in the browser ----------------------------------------------------------


def _log_in(page: Any, hub: Hub, user: str) -> None:
    page.goto(f"{hub.base}/hub/login")
    page.fill("#username_input", user)
    page.fill("#password_input", hub.password)
    page.click("#login_submit")
    page.wait_for_url(re.compile(r".*/(hub/home|hub/spawn.*|user/.*)"), timeout=120_000)


def _open_link(page: Any, link: str) -> None:
    """Open the nbgitpuller link: the server starts if it must, the course is pulled, START_HERE opens."""
    page.goto(link)
    page.wait_for_url(re.compile(rf".*/lab/tree/{REPO_NAME}/START_HERE\.ipynb.*"), timeout=300_000)
    _wait_notebook(page, "START_HERE.ipynb")


def _wait_notebook(page: Any, name: str, timeout: float = 180_000) -> None:
    page.wait_for_function(
        """(name) => {
            const tab = [...document.querySelectorAll('.lm-TabBar-tab.lm-mod-current .lm-TabBar-tabLabel')]
                .some((t) => t.textContent === name);
            return tab && document.querySelectorAll('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-Cell').length > 0;
        }""",
        arg=name,
        timeout=timeout,
    )
    wait_idle(page, timeout)


def _open(page: Any, hub: Hub, user: str, path: str, home: Path) -> Any:
    count = len(json.loads((home / REPO_NAME / path).read_text(encoding="utf-8"))["cells"])
    page.goto(f"{hub.base}/user/{user}/lab/tree/{REPO_NAME}/{path}?reset")
    _wait_notebook(page, Path(path).name)
    page.wait_for_function(
        "n => document.querySelectorAll('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-Cell').length === n",
        arg=count,
        timeout=60_000,
    )
    return page.locator(".jp-NotebookPanel:not(.lm-mod-hidden) .jp-Cell")


def _save(page: Any) -> None:
    page.keyboard.press("Control+s")
    page.wait_for_function(
        "() => document.querySelectorAll('.lm-TabBar-tab.jp-mod-dirty').length === 0", timeout=60_000
    )
    page.wait_for_timeout(1000)


def _nonblank(png: bytes) -> float:
    """The share of the picture's pixels that differ from its most common colour (the background)."""
    import numpy as np
    from PIL import Image

    img = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).reshape(-1, 3)
    _, counts = np.unique(img, axis=0, return_counts=True)
    return float(1.0 - counts.max() / counts.sum())


def _external(requests: list[str]) -> list[str]:
    out = []
    for url in requests:
        parts = urlparse(url)
        if parts.scheme in ("data", "blob", "about"):
            continue
        if parts.hostname != "127.0.0.1":
            out.append(url)
    return out


def _student_works(page: Any, hub: Hub, user: str, link: str) -> None:
    home = hubctl.home(user)
    _log_in(page, hub, user)
    _open_link(page, link)
    page.locator(".jp-RenderedMarkdown", has_text="start here").first.wait_for(timeout=60_000)
    page.screenshot(path=str(ARTIFACTS / f"hub_{user}_1_start_here.png"))

    # lecture 03: Run All, the 3-D panel draws
    _open(page, hub, user, LECTURE, home)
    run_all(page)
    box = viewers(page).first
    box.wait_for(timeout=60_000)
    box.scroll_into_view_if_needed()
    page.wait_for_function("b => b.__puma.poseRenders >= 1", arg=box.element_handle(), timeout=60_000)
    state = box.evaluate(VIEWER_STATE)
    assert state["hasWebGL"], f"{user}: lecture 03's panel has no WebGL canvas"
    assert state["width"] > 300 and state["height"] > 300, state
    share = _nonblank(box.locator("canvas").screenshot())
    assert share > 0.02, f"{user}: lecture 03's 3-D panel is blank ({share:.1%} of its pixels drawn)"
    box.screenshot(path=str(ARTIFACTS / f"hub_{user}_2_lecture03_panel.png"))
    _save(page)

    # exercise 3, question 1: the student's answer, then the self-check under it
    cells = _open(page, hub, user, EXERCISE, home)
    nb = json.loads((home / REPO_NAME / EXERCISE).read_text(encoding="utf-8"))
    ids = [c.get("id") for c in nb["cells"]]
    first, answer, selfcheck = ids.index("ex03-01"), ids.index("ex03-03"), ids.index("ex03-04")
    cells.nth(answer).locator(".cm-content").click()
    page.keyboard.press("Control+a")
    page.keyboard.insert_text(ANSWER.format(user=user))
    cells.nth(first).locator(".cm-content").click()
    for _ in range(selfcheck - first + 1):
        page.keyboard.press("Shift+Enter")
    out = cells.nth(selfcheck).locator(".jp-OutputArea")
    page.wait_for_function("el => /passed|FAILED|Error/.test(el.innerText)", arg=out.element_handle(), timeout=120_000)
    text = out.inner_text()
    assert "passed" in text and "FAILED" not in text, f"{user}: the self-check says {text!r}"
    cells.nth(answer).scroll_into_view_if_needed()
    page.screenshot(path=str(ARTIFACTS / f"hub_{user}_3_exercise03_selfcheck.png"))
    _save(page)
    saved = json.loads((home / REPO_NAME / EXERCISE).read_text(encoding="utf-8"))
    assert f"the answer of {user}" in "".join(saved["cells"][answer]["source"])


def _instructor_updates(edition: Path, git: GitServer) -> None:
    """The instructor changes a lecture's text and an exercise's text (as the edition writes them), commits, pushes."""
    import nbformat

    for path, cell_id, note in ((LECTURE, "c0cb8036", LECTURE_NOTE), (EXERCISE, "ex03-02", EXERCISE_NOTE)):
        nb = nbformat.read(edition / path, as_version=4)
        cell = next(c for c in nb.cells if c.get("id") == cell_id)
        assert cell.cell_type == "markdown", (path, cell_id)
        cell.source = cell.source.rstrip("\n") + "\n\n" + note
        nbformat.write(nb, edition / path)
    hubctl._run([*hubctl.GIT, "commit", "-q", "-am", "Week 5: a note in lecture 03 and a hint in exercise 3"],
                cwd=edition)  # fmt: skip
    git.push()


def _student_pulls_again(page: Any, hub: Hub, user: str, link: str) -> None:
    import nbformat

    home = hubctl.home(user)
    _open_link(page, link)
    # on disk: the instructor's text arrived, the student's answer and outputs stayed, the notebooks are valid
    lecture = nbformat.read(home / REPO_NAME / LECTURE, as_version=4)
    exercise = nbformat.read(home / REPO_NAME / EXERCISE, as_version=4)
    nbformat.validate(lecture)
    nbformat.validate(exercise)
    assert any(LECTURE_NOTE in c.source for c in lecture.cells), f"{user}: the lecture's change did not arrive"
    assert any(EXERCISE_NOTE in c.source for c in exercise.cells), f"{user}: the exercise's change did not arrive"
    answer = next(c for c in exercise.cells if c.get("id") == "ex03-03")
    assert f"the answer of {user}" in answer.source, f"{user}: the answer was lost: {answer.source!r}"
    assert any(c.get("outputs") for c in lecture.cells if c.cell_type == "code"), f"{user}: the lecture's outputs"

    # in JupyterLab: the same, as the student sees it
    _open(page, hub, user, LECTURE, home)
    note = page.locator(".jp-RenderedMarkdown", has_text=LECTURE_NOTE)
    note.scroll_into_view_if_needed()
    assert note.is_visible()
    page.screenshot(path=str(ARTIFACTS / f"hub_{user}_4_lecture03_updated.png"))
    cells = _open(page, hub, user, EXERCISE, home)
    hint = page.locator(".jp-RenderedMarkdown", has_text=EXERCISE_NOTE)
    hint.scroll_into_view_if_needed()
    assert hint.is_visible()
    ids = [c.get("id") for c in exercise.cells]
    assert f"the answer of {user}" in cells.nth(ids.index("ex03-03")).inner_text()
    page.screenshot(path=str(ARTIFACTS / f"hub_{user}_5_exercise03_updated.png"))


# ---- the test ------------------------------------------------------------------------------------


def test_two_students_and_an_update(classroom: dict[str, Any]) -> None:
    ARTIFACTS.mkdir(exist_ok=True)
    hub: Hub = classroom["hub"]
    git: GitServer = classroom["git"]
    link = nbgitpuller_link(hub.base, git.url, branch="main", path="START_HERE.ipynb")
    requests: dict[str, list[str]] = {u: [] for u in STUDENTS}
    with browser() as chromium:
        pages = {}
        for user in STUDENTS:
            context = chromium.new_context(viewport={"width": 1400, "height": 1000}, device_scale_factor=1)
            page = context.new_page()
            page.on("request", lambda r, u=user: requests[u].append(r.url))
            pages[user] = page
            _student_works(page, hub, user, link)

        # the image's course package, not a copy in the home folder, and the student cannot change it
        for user in STUDENTS:
            for where in (LECTURE, EXERCISE):
                res = hubctl.run_in_kernel(
                    hub, user, f"{REPO_NAME}/{where}",
                    ["import os, puma_course; d = os.path.dirname(puma_course.__file__); "
                     "print(d); print(os.access(d, os.W_OK)); print(os.path.expanduser('~'))"],
                )  # fmt: skip
                pkg, writable, home = res[0]["outputs"].split()
                assert pkg.startswith(str(classroom["env"])), f"{user} imports puma_course from {pkg}"
                assert not pkg.startswith(home) and writable == "False", (pkg, writable, home)

        _instructor_updates(classroom["edition"], git)
        for user in STUDENTS:
            _student_pulls_again(pages[user], hub, user, link)

    for user in STUDENTS:
        assert requests[user], f"{user}: no request recorded"
        outside = _external(requests[user])
        assert not outside, f"{user}'s browser asked hosts other than 127.0.0.1: {outside[:10]}"


def test_the_image_runs_lecture_03_under_nbclient(classroom: dict[str, Any], tmp_path: Path) -> None:
    """The environment built from the edition's binder/requirements.txt (the image) runs lecture 03 headless."""
    import subprocess

    env: Path = classroom["env"]
    work = tmp_path / "notebooks"
    work.mkdir()
    src = classroom["edition"] / LECTURE
    (work / src.name).write_bytes(src.read_bytes())
    code = (
        "import sys, nbformat, nbclient\n"
        "nb = nbformat.read(sys.argv[1], as_version=4)\n"
        "nbclient.NotebookClient(nb, timeout=600, kernel_name='python3',"
        " resources={'metadata': {'path': sys.argv[2]}}).execute()\n"
        "print(sum(1 for c in nb.cells if c.cell_type == 'code' and c.outputs))\n"
    )
    done = subprocess.run(
        [str(env / "bin" / "python"), "-c", code, str(work / src.name), str(work)],
        capture_output=True,
        text=True,
        timeout=900,
        env={"PATH": f"{env}/bin:/usr/bin:/bin", "HOME": str(tmp_path), "MPLBACKEND": "Agg"},
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert int(done.stdout.split()[-1]) > 5, done.stdout

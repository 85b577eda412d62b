"""Drive JupyterLab in Debian's Chromium with Playwright: the harness of the browser tests and the benchmark.

:class:`Lab` starts ``jupyter lab`` on 127.0.0.1 (a free port, a random token) serving a
temporary copy of the lectures (so nothing the browser does can change the committed
notebooks), started as ``puma-course lab`` starts it (:func:`puma_course.cli.lab_command`) with
empty settings and workspace folders of its own, so every JupyterLab setting is the default a
student gets (windowed notebooks included); no news, no update check: nothing leaves the machine.
It stops the server by its PID. :func:`browser` launches the system Chromium (Playwright's own
browser download does not work offline).

One server per pytest worker (the session fixture ``lab`` of ``tests/browser/conftest.py``) serves every lecture;
:class:`Tab` opens one lecture once and runs it once for all the checks made on it (``tests/browser/checks_*.py``).
Used by the browser tests and ``benchmarks/bench_viewer.py``.
"""

from __future__ import annotations

import json
import os
import random
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOKS = ROOT / "notebooks"
CHROMIUM_CANDIDATES = ("/usr/bin/chromium", "/usr/bin/chromium-browser")
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]


def chromium_path() -> str | None:
    """Debian's Chromium, or ``$PUMA_CHROMIUM``, or None."""
    env = os.environ.get("PUMA_CHROMIUM")
    if env:
        return env if Path(env).exists() else None
    return next((p for p in CHROMIUM_CANDIDATES if Path(p).exists()), None)


def missing() -> str | None:
    """Why the browser tests cannot run here (None when they can)."""
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "Playwright is not installed (pip install -e '.[dev]')"
    if chromium_path() is None:
        return "Chromium is not installed (as root: apt-get install -y chromium; or set PUMA_CHROMIUM)"
    return None


def _free_port() -> int:
    """A free port on 127.0.0.1: the first free one of ``$PUMA_LAB_PORTS`` ("8800-8849") if set, else any."""
    lo, _, hi = os.environ.get("PUMA_LAB_PORTS", "0").partition("-")
    ports = list(range(int(lo), int(hi or lo) + 1))
    random.shuffle(ports)  # two servers started at once rarely pick the same one
    for port in ports:
        with socket.socket() as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
            return int(s.getsockname()[1])
    raise RuntimeError(f"no free port in PUMA_LAB_PORTS={os.environ['PUMA_LAB_PORTS']}")


class Lab:
    """A JupyterLab server on 127.0.0.1 over a temporary copy of ``notebooks/``; stop() ends it by PID."""

    def __init__(self, notebooks: Path = NOTEBOOKS) -> None:
        self.tmp = Path(tempfile.mkdtemp(prefix="puma-lab-"))
        self.root = self.tmp / "notebooks"
        shutil.copytree(notebooks, self.root, ignore=shutil.ignore_patterns(".ipynb_checkpoints"))
        self.port = _free_port()
        self.token = secrets.token_hex(16)
        # an empty settings folder: every JupyterLab setting at its default, as `puma-course lab` runs it
        # (windowed notebooks, autosave on); only the user's own settings are kept out of the test
        settings = self.tmp / "settings"
        settings.mkdir()
        env = dict(os.environ)
        env.update(
            JUPYTERLAB_SETTINGS_DIR=str(settings),
            JUPYTERLAB_WORKSPACES_DIR=str(self.tmp / "workspaces"),
            JUPYTER_RUNTIME_DIR=str(self.tmp / "runtime"),
            JUPYTER_DATA_DIR=str(self.tmp / "data"),
            PYDEVD_DISABLE_FILE_VALIDATION="1",
        )
        env.pop("MPLBACKEND", None)
        self.log = open(self.tmp / "server.log", "wb")  # noqa: SIM115 - closed in stop()
        for attempt in range(3):  # a port found free may be taken by another server before this one binds it
            cmd = self.command()
            self.proc = subprocess.Popen(cmd, stdout=self.log, stderr=subprocess.STDOUT, env=env, cwd=self.root)
            try:
                self._wait_ready()
                break
            except RuntimeError:
                if attempt == 2 or "is not available" not in self.server_log():
                    self.stop()
                    raise
                self.port = _free_port()

    def command(self) -> list[str]:
        """``puma-course lab``'s own command line (:func:`puma_course.cli.lab_command`) plus the server's address.

        The extra options only choose where the server listens and turn off what would reach the
        network (news, update check, extension manager): no JupyterLab setting differs from its default.
        """
        from puma_course.cli import lab_command

        extra = [
            "--ServerApp.ip=127.0.0.1",
            f"--ServerApp.port={self.port}",
            "--ServerApp.port_retries=0",
            f"--IdentityProvider.token={self.token}",
            "--LabApp.news_url=",
            "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
            "--LabApp.extension_manager=readonly",
        ]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            extra.append("--allow-root")
        cmd = lab_command(self.root, extra, no_browser=True)
        cmd[0] = sys.executable
        return cmd

    @property
    def base(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def url(self, notebook: str) -> str:
        return f"{self.base}/lab/tree/{notebook}?reset&token={self.token}"

    def _wait_ready(self, timeout: float = 60.0) -> None:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if self.proc.poll() is not None:
                raise RuntimeError(f"jupyter lab exited with {self.proc.returncode}: {self.server_log()[-2000:]}")
            try:
                with urllib.request.urlopen(f"{self.base}/api/status?token={self.token}", timeout=2) as r:
                    if r.status == 200:
                        return
            except OSError:
                time.sleep(0.3)
        self.stop()
        raise TimeoutError(f"jupyter lab did not answer on {self.base} in {timeout} s")

    def shutdown_kernels(self) -> None:
        """Shut down every kernel of the server (a lecture's checks are done: its kernel's memory is given back)."""
        try:  # the sessions first (a notebook opened again then starts a kernel of its own), then any kernel left
            for kind in ("sessions", "kernels"):
                with urllib.request.urlopen(f"{self.base}/api/{kind}?token={self.token}", timeout=10) as r:
                    items = json.loads(r.read())
                for item in items:
                    url = f"{self.base}/api/{kind}/{item['id']}?token={self.token}"
                    urllib.request.urlopen(urllib.request.Request(url, method="DELETE"), timeout=30).close()
        except OSError:
            pass  # the server is gone: nothing to give back

    def server_log(self) -> str:
        self.log.flush()
        return (self.tmp / "server.log").read_text(errors="replace")

    def stop(self) -> None:
        """Stop the server by its PID (SIGINT twice is Jupyter's own shutdown; then SIGKILL), remove the copy."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            time.sleep(0.3)
            if self.proc.poll() is None:
                self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=15)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(timeout=5)
        self.log.close()
        shutil.rmtree(self.tmp, ignore_errors=True)

    def __enter__(self) -> Lab:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.stop()


@contextmanager
def browser() -> Iterator[Any]:
    """Playwright's Chromium, the system one (``executable_path``), headless, sandbox and network extras off."""
    from playwright.sync_api import sync_playwright

    path = chromium_path()
    if path is None:
        raise RuntimeError(missing())
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=path, headless=True, args=CHROMIUM_ARGS)
        try:
            yield b
        finally:
            b.close()


# ---- pages -------------------------------------------------------------------------------------


def open_notebook(page: Any, lab: Lab, name: str, timeout: float = 60_000) -> None:
    """Open a notebook in JupyterLab and wait until all its cells are on the page and its kernel is idle."""
    count = len(json.loads((lab.root / name).read_text(encoding="utf-8"))["cells"])
    page.goto(lab.url(name))
    page.wait_for_function(
        "n => document.querySelectorAll('.jp-Notebook .jp-Cell').length === n", arg=count, timeout=timeout
    )
    wait_idle(page, timeout)


def wait_idle(page: Any, timeout: float = 60_000) -> None:
    """Wait until the notebook's kernel status reads idle."""
    page.wait_for_function(
        """() => {
            const s = document.querySelector('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-Toolbar-kernelStatus, '
                + '.jp-NotebookPanel .jp-KernelStatus, .jp-Notebook-ExecutionIndicator');
            const t = s ? (s.getAttribute('data-status') || s.getAttribute('title') || s.textContent || '') : '';
            return /idle/i.test(t);
        }""",
        timeout=timeout,
    )


def run_all(page: Any, timeout: float = 240_000) -> None:
    """Clear the outputs, run every cell (menu Run > Run All Cells), wait until none is queued or running.

    The menu is tried again when no cell has started after 30 s (a click that landed while the
    page was still settling); on a time-out a screenshot is left in tests/artifacts/.
    """
    prompts = "[...document.querySelectorAll('.jp-Notebook .jp-CodeCell .jp-InputPrompt')]"
    started = f"() => {prompts}.some((p) => /\\[(\\*|\\d+)\\]/.test(p.textContent))"
    page.locator(".jp-NotebookPanel .jp-Cell").first.click()
    # clear the saved outputs first, so the prompts' numbers below are this run's
    page.get_by_role("menuitem", name="Edit", exact=True).click()
    page.get_by_role("menuitem", name="Clear Outputs of All Cells", exact=True).click()
    page.wait_for_function(f"() => !{prompts}.some((p) => /\\d/.test(p.textContent))", timeout=30_000)
    for attempt in range(2):
        page.get_by_role("menuitem", name="Run", exact=True).click()
        page.get_by_role("menuitem", name="Run All Cells", exact=True).click()
        try:
            page.wait_for_function(started, timeout=30_000)
            break
        except Exception:
            if attempt:
                _snapshot(page, "run_all_not_started")
                raise
    try:
        page.wait_for_function(
            """() => {
                const prompts = [...document.querySelectorAll('.jp-Notebook .jp-CodeCell .jp-InputPrompt')];
                return prompts.length > 0 && prompts.every((p) => /\\[\\d+\\]/.test(p.textContent));
            }""",
            timeout=timeout,
        )
        wait_idle(page, timeout)
    except Exception:
        _snapshot(page, "run_all_timeout")
        raise


def _snapshot(page: Any, name: str) -> None:
    """A screenshot of the whole page for a failure's diagnosis (tests/artifacts/, git-ignored)."""
    out = ROOT / "tests" / "artifacts"
    out.mkdir(exist_ok=True)
    page.screenshot(path=str(out / f"{name}.png"), full_page=True)


def output_texts(page: Any) -> list[str]:
    """The text of every code cell's output area, in order."""
    return page.eval_on_selector_all(
        ".jp-Notebook .jp-CodeCell",
        "cells => cells.map(c => (c.querySelector('.jp-OutputArea') || {}).innerText || '')",
    )


VIEWER_STATE = """(box) => ({
    poseRenders: box.__puma.poseRenders,
    lastPoseRender: box.__puma.lastPoseRender,
    lastPoseMessage: box.__puma.lastPoseMessage,
    labels: box.__puma.labels,
    hasWebGL: !!box.querySelector('canvas') && !!(box.querySelector('canvas').getContext('webgl2')
        || box.querySelector('canvas').getContext('webgl')),
    width: box.clientWidth, height: box.clientHeight,
})"""


def viewers(page: Any) -> Any:
    return page.locator(".jp-Notebook .puma-viewer")


def install_key_clock(page: Any) -> None:
    """Record the time of every key press (capture phase, before the slider sees it) in ``window.__pumaKeyT``."""
    page.evaluate(
        """() => { if (!window.__pumaKeyClock) { window.__pumaKeyClock = true;
            document.addEventListener('keydown', () => { window.__pumaKeyT = performance.now(); }, true); } }"""
    )


def press_and_time(page: Any, handle: Any, box: Any, key: str = "ArrowRight", timeout: float = 10_000) -> float:
    """Press ``key`` on a slider handle; milliseconds from the key press to the viewer's repaint of the new pose."""
    before = box.evaluate("b => b.__puma.poseRenders")
    handle.press(key)
    box.page.wait_for_function(
        "([b, n]) => b.__puma.poseRenders > n", arg=[box.element_handle(), before], timeout=timeout
    )
    t_key = page.evaluate("() => window.__pumaKeyT")
    t_draw = box.evaluate("b => b.__puma.lastPoseRender")
    return float(t_draw - t_key)


def press_and_time_parts(page: Any, handle: Any, box: Any, key: str = "ArrowRight") -> tuple[float, float]:
    """Like :func:`press_and_time`: (key press -> repaint, key press -> the kernel's new pose arrives) in ms."""
    total = press_and_time(page, handle, box, key)
    t_key = page.evaluate("() => window.__pumaKeyT")
    t_msg = box.evaluate("b => b.__puma.lastPoseMessage")
    return total, float(t_msg - t_key)


def run_by_keyboard(page: Any, lab: Lab, name: str) -> int:
    """Shift+Enter on every cell from the first (keys only); returns the number of cells."""
    n = len(json.loads((lab.root / name).read_text(encoding="utf-8"))["cells"])
    page.locator(".jp-Notebook").focus()  # the notebook has the keyboard focus, as after opening it
    page.keyboard.press("Escape")
    page.keyboard.press("Control+Home")
    for _ in range(n):
        page.keyboard.press("Shift+Enter")
        page.wait_for_timeout(40)
    page.wait_for_function(
        """() => [...document.querySelectorAll('.jp-Notebook .jp-CodeCell .jp-InputPrompt')]
            .every((p) => !/\\[\\*\\]/.test(p.textContent))""",
        timeout=300_000,
    )
    wait_idle(page, 300_000)
    return n


def new_page(chromium: Any) -> Any:
    """A page in a context of its own (1400 x 1000), its uncaught errors gathered in ``page.errors``."""
    context = chromium.new_context(viewport={"width": 1400, "height": 1000}, device_scale_factor=1)
    pg = context.new_page()
    errors: list[str] = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.errors = errors
    return pg


class Tab:
    """One lecture in the worker's JupyterLab, opened once and run once for every check made on it.

    :meth:`opened` is the notebook as a student first opens it (saved outputs, untrusted, no cell run);
    :meth:`executed` is the same page after every cell ran: Shift+Enter on every cell (keys alone) for
    the lectures walked by keyboard (``by_keyboard``), else the menu's Run All after clearing the outputs.
    A check that wants the opened notebook after the run gets a fresh page (correct in any order; the
    test modules order the checks so that it does not happen). ``dirty_after_open`` is the count of tabs
    JupyterLab marked modified half a second after the notebook opened.
    """

    def __init__(self, chromium: Any, lab: Lab, name: str, by_keyboard: bool = False) -> None:
        self.chromium, self.lab, self.name, self.by_keyboard = chromium, lab, name, by_keyboard
        self.page: Any = None
        self.ran = False
        self.opens = 0
        self.dirty_after_open = -1
        self._open()

    def _open(self) -> None:
        self.close()
        if self.opens:  # as committed, not as the run before autosaved it
            shutil.copyfile(NOTEBOOKS / self.name, self.lab.root / self.name)
        self.page = new_page(self.chromium)
        open_notebook(self.page, self.lab, self.name)
        self.page.wait_for_timeout(500)
        self.dirty_after_open = self.page.locator(".lm-DockPanel-tabBar .lm-TabBar-tab.jp-mod-dirty").count()
        self.ran = False
        self.opens += 1

    def opened(self) -> Any:
        if self.ran:
            self._open()
        return self.page

    def executed(self) -> Any:
        if not self.ran:
            if self.by_keyboard:
                run_by_keyboard(self.page, self.lab, self.name)
            else:
                run_all(self.page)
            self.ran = True
        return self.page

    def close(self) -> None:
        if self.page is not None:
            self.page.context.close()
            self.page = None
            self.lab.shutdown_kernels()

"""A real JupyterHub on 127.0.0.1 serving the student edition: the harness of the hub test and the load run.

:func:`make_edition` writes the student edition into a folder (``puma-course edition DIR`` where the
command exists, otherwise a stand-in copying what the edition holds) and makes it a git repository;
:class:`GitServer` publishes it over git's "dumb" HTTP protocol from a local web server, as a course's
git host would; :func:`single_user_env` builds the single-user environment the way an image is built
(a fresh venv outside every home folder, owned by root: the edition's ``binder/requirements.txt``
installed from the edition's folder, plus JupyterLab and JupyterHub's single-user server, as the image's
base brings them); :class:`Hub` starts ``jupyterhub`` (the configurable-http-proxy from npm, the dummy
authenticator with a password, ``LocalProcessSpawner`` with system users made by :func:`make_users`)
and stops it by its PID.

Ports come from ``PUMA_HUB_PORTS`` (``LOW-HIGH``, default 9000-9099): the hub, the proxy's API, the
hub's internal port and the git server take the first four, the single-user servers the rest.
"""

from __future__ import annotations

import asyncio
import json
import os
import pwd
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
import uuid
from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
#: what the student edition holds (issue 19): the stand-in copies these
EDITION_ITEMS = ("START_HERE.ipynb", "notebooks", "exercises", "figures", "puma_course", "pyproject.toml",
                 "README.md", "LICENSE")  # fmt: skip
REPO_NAME = "puma-course"
GIT = [
    "git",
    "-c",
    "user.name=Instructor",
    "-c",
    "user.email=instructor@example.invalid",
    "-c",
    "init.defaultBranch=main",
]


def ports() -> range:
    low, high = (int(x) for x in os.environ.get("PUMA_HUB_PORTS", "9000-9099").split("-"))
    return range(low, high + 1)


def chp_path() -> str | None:
    """configurable-http-proxy (npm): on PATH, or in ``.ci/node_modules/.bin`` where ``.ci/run`` may put it."""
    found = shutil.which("configurable-http-proxy")
    if found:
        return found
    local = ROOT / ".ci" / "node_modules" / ".bin" / "configurable-http-proxy"
    return str(local) if local.exists() else None


def why_not() -> str | None:
    """Why a hub cannot start here (None when it can)."""
    if sys.platform != "linux":
        return "LocalProcessSpawner with system users needs Linux"
    if os.geteuid() != 0:
        return "the hub test makes system users and spawns as them: run it as root"
    if shutil.which("useradd") is None or shutil.which("userdel") is None:
        return "useradd/userdel are missing"
    if chp_path() is None:
        return "configurable-http-proxy is missing (npm install -g configurable-http-proxy; .ci/run does it)"
    if shutil.which("git") is None:
        return "git is missing"
    if base_python() is None:
        return "no Python every user may run with venv (apt-get install python3-venv, or set PUMA_HUB_PYTHON)"
    try:
        import jupyterhub  # noqa: F401
    except ImportError:
        return "jupyterhub is not installed (pip install -e '.[dev]')"
    return None


def _run(cmd: list[str], **kw: Any) -> subprocess.CompletedProcess[str]:
    return subprocess.run(cmd, check=True, text=True, capture_output=True, **kw)


def _open_tmp(prefix: str) -> Path:
    """A temporary folder the students' processes can read (mkdtemp makes it 0700)."""
    path = Path(tempfile.mkdtemp(prefix=prefix))
    path.chmod(0o755)
    return path


# ---- the edition and its git server -------------------------------------------------------------


def make_edition(dest: Path) -> Path:
    """Write the student edition into ``dest`` and commit it (branch ``main``): the instructor's clone.

    Uses ``puma-course edition DIR`` when that command exists; otherwise (until it lands) a stand-in
    copying :data:`EDITION_ITEMS`. Either way the repo2docker files of :func:`puma_course.hub.write_binder_files`
    are there.
    """
    from puma_course.hub import write_binder_files

    exe = Path(sys.executable).with_name("puma-course")
    has_edition = exe.exists() and subprocess.run([str(exe), "edition", "--help"], capture_output=True).returncode == 0
    if has_edition:
        _run([str(exe), "edition", str(dest)])
    else:
        dest.mkdir(parents=True, exist_ok=True)
        skip = shutil.ignore_patterns("__pycache__", ".ipynb_checkpoints", "*.egg-info")
        for item in EDITION_ITEMS:
            src = ROOT / item
            (shutil.copytree(src, dest / item, ignore=skip) if src.is_dir() else shutil.copy2(src, dest / item))
    if not (dest / "binder" / "requirements.txt").exists():
        write_binder_files(dest)
    if not (dest / ".git").exists():
        _run([*GIT, "init", "-q", "-b", "main"], cwd=dest)
    _run([*GIT, "add", "-A"], cwd=dest)
    _run([*GIT, "commit", "-q", "-m", "The student edition"], cwd=dest)
    return dest


class GitServer:
    """A bare clone of the edition served by ``git daemon`` (the git:// protocol) on 127.0.0.1, as a course's git host.

    (git's smart protocol: nbgitpuller clones with ``--depth 1``, which the "dumb" HTTP protocol cannot serve.)
    """

    def __init__(self, edition: Path, port: int) -> None:
        self.tmp = _open_tmp("puma-git-")
        self.bare = self.tmp / REPO_NAME
        _run(["git", "clone", "-q", "--bare", str(edition), str(self.bare)])
        self.edition = edition
        self.port = port
        self.log = open(self.tmp / "daemon.log", "wb")  # noqa: SIM115 - closed in stop()
        self.proc = subprocess.Popen(
            [
                "git",
                "daemon",
                "--export-all",
                "--reuseaddr",
                f"--base-path={self.tmp}",
                "--listen=127.0.0.1",
                f"--port={port}",
                "--informative-errors",
                str(self.tmp),
            ],  # fmt: skip
            stdout=self.log,
            stderr=subprocess.STDOUT,
        )
        end = time.monotonic() + 20
        while subprocess.run(["git", "ls-remote", self.url], capture_output=True).returncode != 0:
            if self.proc.poll() is not None or time.monotonic() > end:
                self.stop()
                raise RuntimeError(f"git daemon did not serve {self.url}")
            time.sleep(0.3)

    @property
    def url(self) -> str:
        return f"git://127.0.0.1:{self.port}/{REPO_NAME}"

    def push(self) -> None:
        """Publish the edition's new commits (what ``git push`` to a course's git host does)."""
        _run([*GIT, "push", "-q", str(self.bare), "main"], cwd=self.edition)

    def stop(self) -> None:
        _stop(self.proc)
        self.log.close()
        shutil.rmtree(self.tmp, ignore_errors=True)


# ---- the single-user environment: the image ---------------------------------------------------


def base_python() -> str | None:
    """A Python every user may run (an image's interpreter): ``$PUMA_HUB_PYTHON``, /usr/bin/python3, or ours."""
    for cand in (os.environ.get("PUMA_HUB_PYTHON"), "/usr/bin/python3", sys.executable):
        if cand and Path(cand).exists() and _world_usable(Path(cand).resolve()):
            ok = subprocess.run([cand, "-c", "import venv, ensurepip"], capture_output=True).returncode == 0
            if ok:
                return cand
    return None


def _world_usable(path: Path) -> bool:
    """Every user can reach and run ``path`` (each folder above it is world-searchable)."""
    if not path.stat().st_mode & 0o005:
        return False
    return all(p.stat().st_mode & 0o001 for p in path.parents)


def single_user_env(edition: Path) -> Path:
    """The single-user environment: a venv (root-owned, outside every home) with ``binder/requirements.txt``.

    pip runs from the edition's top folder, as repo2docker runs it; JupyterLab and JupyterHub (for
    ``jupyterhub-singleuser``, the same version as the hub's) are what an image's base brings. The venv
    is kept in ``$PUMA_HUB_ENV_CACHE`` (default /var/tmp), named by a hash of the requirements, the
    edition's ``pyproject.toml`` and the JupyterHub version; when it exists only the course package is
    reinstalled (``pip install --no-deps .``). ``PUMA_HUB_FRESH_ENV=1`` builds it from scratch.
    """
    import hashlib

    import jupyterhub

    reuse = os.environ.get("PUMA_HUB_ENV")
    if reuse and (Path(reuse) / "bin" / "jupyterhub-singleuser").exists():
        return Path(reuse)
    py = base_python()
    if py is None:
        raise RuntimeError("no Python that every user may run, with venv and ensurepip (set PUMA_HUB_PYTHON)")
    digest = hashlib.sha256()
    for part in ((edition / "binder" / "requirements.txt").read_bytes(), (edition / "pyproject.toml").read_bytes(),
                 jupyterhub.__version__.encode(), py.encode()):  # fmt: skip
        digest.update(part)
    cache = Path(os.environ.get("PUMA_HUB_ENV_CACHE", "/var/tmp"))
    env = cache / f"puma-course-hub-env-{digest.hexdigest()[:12]}"
    pip = [str(env / "bin" / "python"), "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    fresh = os.environ.get("PUMA_HUB_FRESH_ENV") == "1" or not (env / "bin" / "jupyterhub-singleuser").exists()
    if fresh:
        shutil.rmtree(env, ignore_errors=True)
        _run([py, "-m", "venv", str(env)])
        _run([*pip, "-r", "binder/requirements.txt"], cwd=edition)
        _run([*pip, "jupyterlab>=4.0", "ipykernel", f"jupyterhub=={jupyterhub.__version__}"], cwd=edition)
    else:
        _run([*pip, "--no-deps", "--force-reinstall", "."], cwd=edition)
    # what a hub's image sets for a class without internet: JupyterLab does not offer to fetch Jupyter's news
    overrides = env / "share" / "jupyter" / "lab" / "settings" / "overrides.json"
    overrides.parent.mkdir(parents=True, exist_ok=True)
    overrides.write_text(json.dumps({"@jupyterlab/apputils-extension:notification": {"fetchNews": "false"}}))
    for p in [env, *env.rglob("*")]:  # readable by the students, writable by nobody but root
        if not p.is_symlink():
            p.chmod(0o755 if p.is_dir() or os.access(p, os.X_OK) else 0o644)
    return env


# ---- system users ------------------------------------------------------------------------------


def make_users(names: Iterable[str]) -> list[str]:
    """Create system users with a home folder (after removing leftovers of an earlier run)."""
    made = []
    for name in names:
        delete_users([name])
        _run(["useradd", "--create-home", "--shell", "/bin/bash", name])
        made.append(name)
    return made


def delete_users(names: Iterable[str]) -> None:
    for name in names:
        try:
            pwd.getpwnam(name)
        except KeyError:
            continue
        subprocess.run(["pkill", "-KILL", "-u", name], capture_output=True)  # noqa: S603 - only this test's users
        subprocess.run(["userdel", "--remove", name], capture_output=True)


def home(name: str) -> Path:
    return Path(pwd.getpwnam(name).pw_dir)


# ---- the hub -----------------------------------------------------------------------------------

CONFIG = """\
import socket
c = get_config()  # noqa
c.JupyterHub.ip = "127.0.0.1"
c.JupyterHub.port = {hub_port}
c.JupyterHub.hub_ip = "127.0.0.1"
c.JupyterHub.hub_port = {internal_port}
c.ConfigurableHTTPProxy.api_url = "http://127.0.0.1:{proxy_port}"
c.ConfigurableHTTPProxy.command = [{chp!r}]
c.ConfigurableHTTPProxy.auth_token = {proxy_token!r}
c.JupyterHub.db_url = "sqlite:///{tmp}/jupyterhub.sqlite"
c.JupyterHub.cookie_secret_file = "{tmp}/cookie_secret"
c.JupyterHub.pid_file = "{tmp}/jupyterhub.pid"
c.JupyterHub.cleanup_servers = True
c.JupyterHub.check_running_servers = False  # hub statistics are not this test's business

c.JupyterHub.authenticator_class = "dummy"
c.DummyAuthenticator.password = {password!r}
c.Authenticator.allowed_users = set({users!r})

c.JupyterHub.spawner_class = "localprocess"
c.Spawner.ip = "127.0.0.1"
c.Spawner.cmd = ["{env}/bin/jupyterhub-singleuser"]
c.Spawner.default_url = "/lab"
c.Spawner.start_timeout = 300
c.Spawner.http_timeout = 300
c.Spawner.environment = {{"PATH": "{env}/bin:/usr/local/bin:/usr/bin:/bin", "MPLBACKEND": "module://matplotlib_inline.backend_inline"}}
c.Spawner.args = [
    "--LabApp.news_url=",
    "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
    "--LabApp.extension_manager=readonly",
]
c.LocalProcessSpawner.shell_cmd = []

PORTS = list(range({low}, {high} + 1))


def pick_port(spawner):
    # the single-user servers' ports stay inside this test's range: user i takes the i-th free one
    users = sorted({users!r})
    start = users.index(spawner.user.name) if spawner.user.name in users else 0
    for port in PORTS[start:] + PORTS[:start]:
        with socket.socket() as s:
            s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
        spawner.port = port
        return
    raise RuntimeError("no free port for a single-user server in {low}-{high}")


c.Spawner.pre_spawn_hook = pick_port

c.JupyterHub.services = [{{"name": "puma-admin", "api_token": {admin_token!r}}}]
c.JupyterHub.load_roles = [
    {{
        "name": "puma-admin",
        "scopes": ["admin:users", "admin:servers", "access:servers", "read:users", "servers"],
        "services": ["puma-admin"],
    }}
]
"""


class Hub:
    """``jupyterhub`` on 127.0.0.1 for ``users`` (password :attr:`password`), single-user servers from ``env``."""

    def __init__(self, users: list[str], env: Path) -> None:
        pr = ports()
        self.port, proxy_port, internal_port = pr[0], pr[1], pr[2]
        busy = [p for p in (self.port, proxy_port, internal_port) if not free(p)]
        if busy:
            raise RuntimeError(f"ports {busy} are in use on 127.0.0.1 (a hub left running?); set PUMA_HUB_PORTS")
        self.tmp = _open_tmp("puma-hub-")
        self.users = list(users)
        self.password = secrets.token_hex(8)
        self.token = secrets.token_hex(24)
        (self.tmp / "jupyterhub_config.py").write_text(
            CONFIG.format(
                hub_port=self.port,
                proxy_port=proxy_port,
                internal_port=internal_port,
                chp=chp_path(),
                proxy_token=secrets.token_hex(24),
                tmp=self.tmp,
                password=self.password,
                users=self.users,
                env=env,
                low=pr[4],
                high=pr[-1],
                admin_token=self.token,
            ),
            encoding="utf-8",
        )
        self.log = open(self.tmp / "hub.log", "wb")  # noqa: SIM115 - closed in stop()
        self.proc = subprocess.Popen(
            [str(Path(sys.executable).with_name("jupyterhub")), "-f", str(self.tmp / "jupyterhub_config.py")],
            stdout=self.log,
            stderr=subprocess.STDOUT,
            cwd=self.tmp,
            start_new_session=True,
        )
        try:
            _wait_http(f"{self.base}/hub/api", self.proc, 90, self.hub_log)
        except Exception:
            self.stop()
            raise

    @property
    def base(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def hub_log(self) -> str:
        if not self.log.closed:
            self.log.flush()
        return (self.tmp / "hub.log").read_text(errors="replace")

    def api(self, method: str, path: str, body: Any = None, timeout: float = 60) -> Any:
        """The Hub's REST API (``/hub/api/...``) with the admin service's token."""
        return request(method, f"{self.base}/hub/api{path}", self.token, body, timeout)

    def user_api(self, user: str, method: str, path: str, body: Any = None, timeout: float = 60) -> Any:
        """A single-user server's Jupyter Server API (``/user/NAME/api/...``) through the proxy."""
        return request(method, f"{self.base}/user/{user}/api{path}", self.token, body, timeout)

    def start_server(self, user: str, timeout: float = 300) -> float:
        """Start ``user``'s server through the REST API; seconds until it answers."""
        t0 = time.monotonic()
        self.ensure_user(user)
        self.api("POST", f"/users/{user}/server")
        while time.monotonic() - t0 < timeout:
            model = self.api("GET", f"/users/{user}")
            server = (model.get("servers") or {}).get("", {})
            if server.get("ready"):
                return time.monotonic() - t0
            time.sleep(0.5)
        raise TimeoutError(f"{user}'s server was not ready in {timeout} s")

    def ensure_user(self, user: str) -> None:
        """Add ``user`` to the hub's database (an allowed user appears there at the first login otherwise)."""
        try:
            self.api("GET", f"/users/{user}")
        except RuntimeError:
            self.api("POST", f"/users/{user}")

    def stop_server(self, user: str) -> None:
        self.api("DELETE", f"/users/{user}/server")

    def pull(self, user: str, repo: str, branch: str = "main", timeout: float = 300) -> str:
        """nbgitpuller's API (``/user/NAME/git-pull/api``, what its page calls): the event stream's text."""
        from urllib.parse import urlencode

        url = f"{self.base}/user/{user}/git-pull/api?" + urlencode({"repo": repo, "branch": branch})
        req = urllib.request.Request(url, headers={"Authorization": f"token {self.token}"})
        with urllib.request.urlopen(req, timeout=timeout) as r:  # noqa: S310 - 127.0.0.1
            text = r.read().decode("utf-8", "replace")
        if '"phase": "finished"' not in text.replace("'", '"'):
            raise RuntimeError(f"nbgitpuller did not finish for {user}: {text[-1500:]}")
        return text

    def stop(self) -> None:
        _stop(self.proc, group=True)
        self.log.close()

    def cleanup(self) -> None:
        shutil.rmtree(self.tmp, ignore_errors=True)


def request(method: str, url: str, token: str, body: Any = None, timeout: float = 60) -> Any:
    data = None if body is None else json.dumps(body).encode()
    req = urllib.request.Request(url, data=data, method=method, headers={"Authorization": f"token {token}"})
    if data is not None:
        req.add_header("Content-Type", "application/json")
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:  # noqa: S310 - 127.0.0.1
            raw = r.read()
    except urllib.error.HTTPError as e:
        raise RuntimeError(f"{method} {url}: {e.code} {e.read()[:500]!r}") from e
    return json.loads(raw) if raw.strip() else None


# ---- code through a kernel (the Jupyter Server API's kernel websocket) ---------------------------


def run_in_kernel(
    hub: Hub, user: str, path: str, sources: list[str], timeout: float = 300, may_fail: Iterable[int] = ()
) -> list[dict[str, Any]]:
    """Open a session for the notebook ``path`` (its kernel starts in the notebook's folder, as JupyterLab's
    does), run each source in turn, end it; per source: its text outputs and seconds.

    Raises ``RuntimeError`` with the traceback when a source fails, unless its index is in ``may_fail``
    (a cell tagged ``raises-exception``, which shows an error on purpose).
    """
    session = hub.user_api(
        user,
        "POST",
        "/sessions",
        {"path": path, "name": Path(path).name, "type": "notebook", "kernel": {"name": "python3"}},
    )
    try:
        # in a thread of its own: the caller may be inside an event loop (Playwright's sync API runs one)
        with ThreadPoolExecutor(1) as pool:
            return pool.submit(
                asyncio.run, _run_sources(hub, user, session["kernel"]["id"], sources, timeout, set(may_fail))
            ).result()
    finally:
        try:
            hub.user_api(user, "DELETE", f"/sessions/{session['id']}")
        except RuntimeError:
            pass


async def _run_sources(
    hub: Hub, user: str, kid: str, sources: list[str], timeout: float, may_fail: set[int]
) -> list[dict[str, Any]]:
    from tornado.httpclient import HTTPRequest
    from tornado.websocket import websocket_connect

    url = f"ws://127.0.0.1:{hub.port}/user/{user}/api/kernels/{kid}/channels"
    ws = await websocket_connect(HTTPRequest(url, headers={"Authorization": f"token {hub.token}"}))
    session = uuid.uuid4().hex
    results = []
    try:
        for index, src in enumerate(sources):
            msg_id = uuid.uuid4().hex
            msg = {
                "header": {
                    "msg_id": msg_id,
                    "username": user,
                    "session": session,
                    "msg_type": "execute_request",
                    "version": "5.3",
                    "date": "",
                },  # fmt: skip
                "parent_header": {},
                "metadata": {},
                "content": {
                    "code": src,
                    "silent": False,
                    "store_history": True,
                    "user_expressions": {},
                    "allow_stdin": False,
                    "stop_on_error": True,
                },  # fmt: skip
                "channel": "shell",
                "buffers": [],
            }
            t0 = time.monotonic()
            await ws.write_message(json.dumps(msg))
            outputs: list[str] = []
            error = None
            while True:
                raw = await asyncio.wait_for(ws.read_message(), timeout)
                if raw is None:
                    raise RuntimeError("the kernel's websocket closed")
                if isinstance(raw, bytes):
                    continue  # a binary message (widget buffers)
                reply = json.loads(raw)
                if reply.get("parent_header", {}).get("msg_id") != msg_id:
                    continue
                kind, content = reply["msg_type"], reply["content"]
                if kind == "stream":
                    outputs.append(content["text"])
                elif kind in ("execute_result", "display_data"):
                    outputs.append(content["data"].get("text/plain", ""))
                elif kind == "error":
                    error = "\n".join(content["traceback"])
                elif kind == "status" and content["execution_state"] == "idle":
                    break
            if error and index not in may_fail:
                raise RuntimeError(f"a cell failed:\n{src[:300]}\n{error[-2000:]}")
            results.append({"outputs": "".join(outputs), "seconds": time.monotonic() - t0})
    finally:
        ws.close()
    return results


def code_cells(path: Path) -> tuple[list[str], set[int]]:
    """A notebook's code cells, and the indexes of those tagged ``raises-exception`` (errors on purpose)."""
    nb = json.loads(path.read_text(encoding="utf-8"))
    cells = [c for c in nb["cells"] if c["cell_type"] == "code"]
    fail = {i for i, c in enumerate(cells) if "raises-exception" in c.get("metadata", {}).get("tags", [])}
    return ["".join(c["source"]) for c in cells], fail


# ---- processes ---------------------------------------------------------------------------------


def _wait_http(url: str, proc: subprocess.Popen[Any], timeout: float, log: Any = None) -> None:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if proc.poll() is not None:
            raise RuntimeError(f"{proc.args} exited with {proc.returncode}: {log()[-3000:] if log else ''}")
        try:
            with urllib.request.urlopen(url, timeout=2):  # noqa: S310 - 127.0.0.1
                return
        except OSError:
            time.sleep(0.3)
    raise TimeoutError(f"{url} did not answer in {timeout} s: {log()[-3000:] if log else ''}")


def _stop(proc: subprocess.Popen[Any], group: bool = False) -> None:
    """SIGTERM (to the process group we started, for the hub and its proxy), then SIGKILL."""
    if proc.poll() is not None:
        return
    if group:
        os.killpg(proc.pid, signal.SIGTERM)
    else:
        proc.terminate()
    try:
        proc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        if group:
            os.killpg(proc.pid, signal.SIGKILL)
        else:
            proc.kill()
        proc.wait(timeout=10)


def free(port: int) -> bool:
    with socket.socket() as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as the servers bind: TIME_WAIT is no obstacle
        try:
            s.bind(("127.0.0.1", port))
        except OSError:
            return False
    return True

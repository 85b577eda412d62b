"""Serve the student edition from a JupyterHub or Binder: its repo2docker files and its nbgitpuller links.

The student edition (``puma-course edition DIR``) is a git repository that a class reaches two ways:

* **Binder / repo2docker** builds an image from it. :func:`write_binder_files` writes
  ``binder/requirements.txt`` (repo2docker's Python configuration file; a ``binder/`` folder makes
  repo2docker ignore every configuration file at the top, so the edition's own ``pyproject.toml`` is
  not installed a second time): the edition's course package with its runtime dependencies only (the
  image brings JupyterLab; the grader, the website and the developer tools stay out), and nbgitpuller,
  so the same image serves a hub's nbgitpuller links.
* **nbgitpuller** clones it into each student's home on the first click of a link and, on every later
  click, commits the student's changes and merges the instructor's with ``git merge -Xours`` (the
  student's side wins where both changed the same lines). The edition is friendly to that merge when
  its notebooks are written the way JupyterLab saves them (so a student's save changes only the lines
  the student changed: the cells run, the answer typed) and when nothing Jupyter writes on its own
  (checkpoints, caches) is tracked: :func:`write_binder_files` also writes the ``.gitignore`` that
  keeps those out (nbgitpuller's "repository best practices").

:func:`nbgitpuller_link` and :func:`binder_link` build the links an instructor hands out.
"""

from __future__ import annotations

from pathlib import Path
from urllib.parse import quote, urlencode

#: what Jupyter, Python and pip write beside the notebooks on their own: never tracked, so never merged
GITIGNORE_LINES = (
    ".ipynb_checkpoints/",
    "__pycache__/",
    "*.py[cod]",
    ".virtual_documents/",
    "*.egg-info/",
    "build/",
    ".DS_Store",
)

REQUIREMENTS = """\
# repo2docker (Binder, Zero to JupyterHub images) installs this with pip from the repository's top folder.
# The course package with its runtime dependencies only: the image brings JupyterLab and the
# single-user server; nbgitpuller lets a hub's links pull the course into the students' home folders.
.
nbgitpuller
"""


def write_binder_files(dest: Path) -> list[Path]:
    """Write the repo2docker/Binder environment and the nbgitpuller-friendly ``.gitignore`` into an edition.

    ``dest`` is the edition's top folder (it holds ``pyproject.toml``). Writes ``binder/requirements.txt``
    and adds the missing lines of :data:`GITIGNORE_LINES` to ``.gitignore`` (keeping its own). Returns the
    files written. Raises ``ValueError`` when ``dest`` is not a folder holding ``pyproject.toml``.
    """
    dest = Path(dest)
    if not (dest / "pyproject.toml").is_file():
        raise ValueError(f"dest: expected the edition's folder, holding pyproject.toml; got {str(dest)!r}")
    binder = dest / "binder"
    binder.mkdir(exist_ok=True)
    req = binder / "requirements.txt"
    req.write_text(REQUIREMENTS, encoding="utf-8")
    ignore = dest / ".gitignore"
    have = ignore.read_text(encoding="utf-8").splitlines() if ignore.exists() else []
    missing = [line for line in GITIGNORE_LINES if line not in have]
    if missing or not ignore.exists():
        text = "\n".join(have + missing).strip("\n") + "\n"
        ignore.write_text(text, encoding="utf-8")
    return [req, ignore]


def nbgitpuller_link(
    hub: str, repo: str, branch: str = "main", path: str = "START_HERE.ipynb", target: str | None = None
) -> str:
    """The nbgitpuller link that pulls ``repo`` into a student's home on ``hub`` and opens ``path`` in JupyterLab.

    The form of nbgitpuller's documentation (its link generator, "JupyterHub" tab):
    ``{hub}/hub/user-redirect/git-pull?repo=...&branch=...&urlpath=lab/tree/{target}/{path}``, where
    ``target`` is the folder the repository lands in (by default the last part of its URL).

    >>> nbgitpuller_link("https://hub.example.edu", "https://git.example.edu/kin/puma-course")
    'https://hub.example.edu/hub/user-redirect/git-pull?repo=https%3A%2F%2Fgit.example.edu%2Fkin%2Fpuma-course&branch=main&urlpath=lab%2Ftree%2Fpuma-course%2FSTART_HERE.ipynb'
    """
    for name, value in (("hub", hub), ("repo", repo), ("branch", branch), ("path", path)):
        if not isinstance(value, str) or not value.strip():
            raise ValueError(f"{name}: expected a non-empty string; got {value!r}")
    folder = target if target is not None else repo.rstrip("/").split("/")[-1]
    if not folder or "/" in folder:
        raise ValueError(f"target: expected a folder name without '/'; got {folder!r}")
    query = urlencode({"repo": repo, "branch": branch, "urlpath": f"lab/tree/{folder}/{path.lstrip('/')}"})
    return f"{hub.rstrip('/')}/hub/user-redirect/git-pull?{query}"


def binder_link(github_repo: str, ref: str = "main", path: str = "START_HERE.ipynb") -> str:
    """The mybinder.org link that builds ``owner/name`` at ``ref`` and opens ``path`` in JupyterLab.

    >>> binder_link("kin-course/puma-course-student")
    'https://mybinder.org/v2/gh/kin-course/puma-course-student/main?urlpath=lab/tree/START_HERE.ipynb'
    """
    if not isinstance(github_repo, str) or github_repo.count("/") != 1 or not all(github_repo.split("/")):
        raise ValueError(f"github_repo: expected 'owner/name'; got {github_repo!r}")
    return f"https://mybinder.org/v2/gh/{github_repo}/{quote(ref, safe='')}?urlpath=lab/tree/{quote(path)}"

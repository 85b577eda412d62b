"""Package-level promises: a light import, a curated namespace, a CI script that fails on failure."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_import_is_light():
    code = (
        "import sys, puma_course\n"
        "heavy = [m for m in ('sympy', 'matplotlib', 'ipywidgets', 'anywidget', 'nbclient', 'IPython')\n"
        "         if m in sys.modules]\n"
        "print(','.join(heavy))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"import puma_course pulled in: {out.stdout.strip()}"


def test_public_names():
    import puma_course

    for name in puma_course.__all__:
        assert hasattr(puma_course, name), name


def test_ci_script_propagates_pytest_failure_and_no_tests():
    text = (ROOT / ".ci" / "run").read_text()
    assert "set -euo pipefail" in text
    assert 'pip install -e ".[dev]"' in text
    assert "python -m pytest" in text
    assert '"$status" -eq 5' in text  # "no tests ran" must not pass CI


def test_readme_commands_match_ci():
    """README's test command is CI's; its first commands install and open the course."""
    readme = (ROOT / "README.md").read_text()
    assert 'python -m pip install -e ".[dev]" && python -m pytest' in readme
    blocks = re.findall(r"```bash\n(.*?)```", readme, flags=re.DOTALL)
    # a venv first, then a student's install (tests/test_readme_start.py runs these lines in a fresh clone)
    assert blocks[0].strip().splitlines()[-2:] == ['python -m pip install -e ".[lab]"', "puma-course lab"]
    # the old start command served notebooks/ only, out of reach of exercises/
    assert "jupyter lab notebooks/" not in readme
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert 'puma-course = "puma_course.cli:main"' in pyproject


def test_ruff_clean():
    """The code base stays ruff-clean (the dev extra installs ruff)."""
    import shutil

    ruff = shutil.which("ruff") or str(Path(sys.executable).with_name("ruff"))
    if not Path(ruff).exists():
        import pytest

        pytest.skip('ruff-clean check not run: ruff is not installed (pip install -e ".[dev]")')
    out = subprocess.run([ruff, "check", "--quiet", str(ROOT)], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stdout + out.stderr

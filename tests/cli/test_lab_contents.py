"""The file manager of ``puma-course lab``: every notebook reaches JupyterLab as its kernel will describe it.

JupyterLab writes the kernel's ``language_info`` (from its ``kernel_info`` reply) into a notebook when
the kernel connects, and a notebook that lacked any of it opens marked modified. The truth here is the
reply of a real IPython kernel, started on this interpreter.
"""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from puma_course.cli.lab_contents import CourseContentsManager, kernel_language_info, with_running_python
from tests.support import ROOT

pytest.importorskip("jupyter_server")


@pytest.fixture(scope="module")
def kernel_reply() -> dict[str, Any]:
    """``language_info`` as a freshly started ``python3`` kernel reports it."""
    from jupyter_client.manager import start_new_kernel

    km, kc = start_new_kernel(kernel_name="python3")
    try:
        return kc.kernel_info(reply=True, timeout=60)["content"]["language_info"]
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=True)


def test_the_filled_in_language_info_is_the_kernels(kernel_reply):
    assert kernel_language_info() == kernel_reply


NOTEBOOKS = ["START_HERE.ipynb", *sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "exercises").glob("*.ipynb"))]


@pytest.mark.parametrize("path", NOTEBOOKS)
def test_start_here_and_every_exercise_open_as_the_kernel_describes_them(kernel_reply, path):
    model = asyncio.run(CourseContentsManager(root_dir=str(ROOT)).get(path))
    assert model["content"]["metadata"]["language_info"] == kernel_reply


def test_a_python_notebook_without_language_info_gets_it_and_others_are_left_alone():
    def nb(meta: dict[str, Any]) -> dict[str, Any]:
        return {"type": "notebook", "content": {"metadata": meta}}

    spec = {"kernelspec": {"name": "python3", "language": "python", "display_name": "Python 3"}}
    filled = with_running_python(nb(dict(spec)), "3.12.4")["content"]["metadata"]["language_info"]
    assert filled == kernel_language_info("3.12.4") and filled["version"] == "3.12.4"
    other = {"kernelspec": {"name": "ir", "language": "R"}, "language_info": {"name": "R", "version": "4.3"}}
    assert with_running_python(nb(dict(other)), "3.12.4")["content"]["metadata"] == other

"""The fixed parts of the student-side ``puma_course``: the self-check stub and the "not available" answers.

These are source texts written into the student-side package (never imported here): every
generated module ends with :data:`MODULE_FOOTER`, whose module ``__getattr__`` turns the
lookup of anything absent into an ``ImportError`` saying that it is not available in this
exercise; the top-level ``__init__`` adds :data:`PACKAGE_FOOTER`, a last-resort import finder that
says the same for absent sub-modules; ``puma_course/grading/__init__.py`` is :data:`GRADING_STUB`.
"""

from __future__ import annotations

__all__ = ["HEADER", "MODULE_FOOTER", "PACKAGE_FOOTER", "GRADING_STUB", "message"]

HEADER = '"""The grader\'s copy of {module} for {exercise}: only what this exercise allows (generated)."""\n'

#: Appended to every generated module; ``{allowed}`` is the exercise's allowed list, as text.
MODULE_FOOTER = """

_ALLOWED_HERE = {allowed!r}


def __getattr__(name):
    if name.startswith("__") and name.endswith("__"):
        raise AttributeError(name)
    raise ImportError(
        f"{{__name__}}.{{name}} is not available in this exercise: write it yourself "
        f"(what this exercise lets you import from puma_course: {{_ALLOWED_HERE}})",
        name=f"{{__name__}}.{{name}}",
    )
"""

#: Appended to the top-level ``__init__``: absent sub-modules fail with the same message.
PACKAGE_FOOTER = '''

class _NotInThisExercise:
    """The last import finder: a ``puma_course`` module that is not here is not available in this exercise."""

    @staticmethod
    def find_spec(fullname, path=None, target=None):
        if fullname.split(".")[0] == "puma_course":
            raise ModuleNotFoundError(
                f"{fullname} is not available in this exercise: write it yourself "
                f"(what this exercise lets you import from puma_course: {_ALLOWED_HERE})",
                name=fullname,
            )
        return None


import sys as _sys

if not any(type(f).__name__ == "_NotInThisExercise" for f in _sys.meta_path):
    _sys.meta_path.append(_NotInThisExercise())
del _sys
'''

#: ``puma_course/grading/__init__.py`` on the student side: the self-check runs in the student's
#: own notebook (against the real package); while grading it answers nothing.
GRADING_STUB = '''"""The self-check while your notebook is graded: a stub (the grader judges your functions itself)."""


def use_exercise(name):
    """Does nothing while grading."""
    return None


def check(question, answer):
    """Does nothing while grading: the grader calls your functions on its own inputs."""
    print(f"{question}: the self-check does not run while grading")
'''


def message(allowed: tuple[str, ...]) -> str:
    """The allowed list as the student reads it in the "not available" message.

    >>> message(()), message(("puma_course.transforms:rodrigues",))
    ('nothing but the self-check', 'puma_course.transforms:rodrigues and the self-check')
    """
    if not allowed:
        return "nothing but the self-check"
    return ", ".join(allowed) + " and the self-check"

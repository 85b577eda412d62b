"""The command line's own output: ``puma-course --help``'s list of commands, and output nobody reads any more.

``--help`` lists a student's commands first, then the instructor's (argparse has one list, in the order the
commands were added). A program reading the output that stops early (``puma-course check ... | head``) ends the
command quietly (:func:`drop_stdout`, exit code :data:`BROKEN_PIPE`), never with a traceback.
Standard library only (cli layer).
"""

from __future__ import annotations

import os
import shutil
import sys
import textwrap

__all__ = ["STUDENT_COMMANDS", "BROKEN_PIPE", "command_list", "drop_stdout"]

#: the commands a student runs, listed first by ``puma-course --help``; every other one is the instructor's
STUDENT_COMMANDS = ("lab", "check")


def command_list(commands: list[tuple[str, str]]) -> str:
    """``puma-course --help``'s list of commands: a student's first, then the instructor's, each with its help.

    >>> print(command_list([("grade", "grade a class"), ("lab", "open JupyterLab")]))
    Manipulator-kinematics course tools.
    <BLANKLINE>
    Commands for students:
      lab              open JupyterLab
    <BLANKLINE>
    Commands for instructors:
      grade            grade a class
    <BLANKLINE>
    `puma-course COMMAND --help` describes a command and its options.
    """
    width = max(shutil.get_terminal_size().columns - 2, 60)

    def rows(names: list[str]) -> str:
        helps = dict(commands)
        return "\n".join(
            textwrap.fill(
                helps[n], width, initial_indent=f"  {n:<15}  ", subsequent_indent=" " * 19, break_on_hyphens=False
            )
            for n in names
        )

    student = [n for n in STUDENT_COMMANDS if n in dict(commands)]
    teacher = [n for n, _ in commands if n not in STUDENT_COMMANDS]
    return (
        "Manipulator-kinematics course tools.\n\n"
        f"Commands for students:\n{rows(student)}\n\n"
        f"Commands for instructors:\n{rows(teacher)}\n\n"
        "`puma-course COMMAND --help` describes a command and its options."
    )


#: the exit code when the reader of the output went away (``| head``): a shell's 128 + SIGPIPE
BROKEN_PIPE = 141


def drop_stdout() -> None:
    """Send what is still to be printed nowhere: the reader of the output is gone (``puma-course ... | head``)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # the buffered rest, flushed at exit, goes there too
        os.close(devnull)
    except (OSError, ValueError):  # no file descriptor (a test's captured output): nothing is flushed at exit
        pass

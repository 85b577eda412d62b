"""Callables made by a factory that can be written to a file and made again (pickled by their recipe).

A judge, a comparison or a mistake's check is a closure over its factory's arguments
(``sign_flip(names)``, ``table_judge(chain_fk, standard_fk)``); :func:`made` wraps one so that
:mod:`pickle` stores the recipe (the factory, by name, and its arguments) instead of the closure.
The student edition stores its public questions this way (:mod:`puma_course.grading.publish.public`),
with the question bank's own functions among the arguments replaced by recorded values.

>>> import pickle
>>> from puma_course.grading.judge.compare import compare_angles_at
>>> cmp = pickle.loads(pickle.dumps(compare_angles_at([0])))
>>> cmp([0.1], np.array([0.1])) is None
True
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np  # noqa: F401 - used by the doctest

__all__ = ["Made", "made", "remake"]

F = TypeVar("F", bound=Callable[..., Any])


class Made:
    """``fn`` as made by ``factory(*args, **kwargs)`` (its attribute ``attr``, when the factory returns an object)."""

    __slots__ = ("fn", "factory", "args", "kwargs", "attr")

    def __init__(
        self,
        fn: Callable[..., Any],
        factory: Callable[..., Any],
        args: tuple[Any, ...],
        kwargs: dict[str, Any],
        attr: str,
    ) -> None:
        self.fn, self.factory, self.args, self.kwargs, self.attr = fn, factory, args, kwargs, attr

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.fn(*args, **kwargs)

    def __reduce__(self) -> tuple[Any, ...]:
        return (remake, (self.factory, self.args, self.kwargs, self.attr))

    def __repr__(self) -> str:
        return f"<{getattr(self.factory, '__name__', 'factory')}(...){'.' + self.attr if self.attr else ''}>"


def made(fn: F, factory: Callable[..., Any], *args: Any, attr: str = "", **kwargs: Any) -> F:
    """Wrap ``fn``, which ``factory(*args, **kwargs)`` made, so that it pickles as that recipe."""
    return Made(fn, factory, args, kwargs, attr)  # type: ignore[return-value]


def remake(factory: Callable[..., Any], args: tuple[Any, ...], kwargs: dict[str, Any], attr: str = "") -> Any:
    """Call the recipe again: ``factory(*args, **kwargs)``, or its attribute ``attr``."""
    out = factory(*args, **kwargs)
    return getattr(out, attr) if attr else out

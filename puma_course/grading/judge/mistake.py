"""A recognisable wrong answer: a :class:`Mistake` is a key (one of :data:`TITLES`) and the check that spots it.

The mistakes themselves are in :mod:`.diagnose` and :mod:`.angle_mistakes`, which both build on this module.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["TITLES", "Check", "Mistake", "base_key", "close", "finite_floats"]

#: Every mistake key the graders emit, with the title an instructor reads in the class summary.
TITLES: dict[str, str] = {
    "transposed": "a transposed rotation (Rᵀ for R)",
    "degrees": "degrees where radians were expected",
    "standard_dh": "the standard (distal) DH link matrix instead of Craig's modified one",
    "order": "factors multiplied in the wrong order (fixed vs moving axes)",
    "unnormalised": "an axis not normalised to length 1",
    "sign_flip": "one row, column or entry with the wrong sign",
    "angle_2pi": "an angle off by a whole turn (2π)",
    "solution_order": "the right solutions in another order",
    "duplicates": "the same solution listed twice",
    "inverse": "the inverse transform (parent and child swapped)",
    "translation": "the inverse's translation is not -Rᵀp",
    "range": "the same rotation, outside the range asked for",
    "printed_formula": "a misprinted formula of the source, used as printed",
    "only_at_zero": "a DH table that is right at q = 0 only",
    "joint_sign": "a joint axis pointing the wrong way",
    "joint_type": "revolute and prismatic joints mixed up",
    "base_frame": "the wrong base: poses measured from another frame than the one the question fixes",
    "tool_frame": "the last frame is not the tool frame the question fixes",
    "straight_start": "the straight start assumed instead of the given bent one",
    "branch": "the other elbow branch",
    "missing_solutions": "solutions missing from the set",
    "not_a_solution": "rows that do not reach the pose",
    "not_nearest": "a solution, but not the nearest one",
    "unwrapped_distance": "angle differences not wrapped to (-π, π]",
    "jump": "a joint jump along the path (a branch switch)",
    "start_jump": "the path does not start at the given configuration",
    "negative_stroke": "the q2 < 0 branch kept",
    "stroke_limit": "a configuration beyond the stroke limit kept",
    "lecture_mechanism": "the lecture's mechanism, not the variant the question describes",
    "joint_line": "a joint turning about a parallel line through the wrong point",
    "unsigned_angle": "the unsigned angle |v × w| instead of the signed one",
    "wrong_axis": "an offset along, or a turn about, the wrong axis",
    "offset_sign": "an offset with the wrong sign",
    "not_minimal": "not Porter's minimal stroke",
    "back_plane": "the arm plane entered from the back",
    "time_scaling": "another time scaling than the one asked for (linear, cubic, t not divided by the duration)",
    "frame_coordinates": "a vector or point written in another frame's coordinates than the one asked for",
    "rotation_sense": "a rotation turned the wrong way (by -θ for θ)",
    "projected_only": "only the approach vector moved into the plane: the frame's other axes not turned with it",
    "not_smallest_turn": "a rotation that brings the approach into the plane, but not the smallest one",
    "joint_zero": "joint values counted from another zero than the one the question fixes",
    "gimbal_lock": "the regular Euler-angle formula used at the gimbal lock (atan2(0, 0))",
    "missing_offset": "a length of the mechanism (a height, an offset) left out of the table",
    "angle_quadrant": "an angle from arcsin or arccos alone, in the wrong quadrant",
    "missing_factor": "a factor of a product left out",
    "off_by_one": "a product of link matrices that starts or stops one link off",
    "lock_threshold": "a gimbal-lock test with another threshold than the one the question states",
}

#: ``check(got, expected, args, reference)``: a message for the student if ``got`` is this mistake, else None.
Check = Callable[[np.ndarray, Any, tuple[Any, ...], Any], str | None]


@dataclass(frozen=True)
class Mistake:
    """A recognisable wrong answer: its ``key`` (one of :data:`TITLES`) and the ``check`` that spots it.

    >>> m = Mistake("degrees", lambda got, exp, args, ref: "degrees!" if got[0] > 7 else None)
    >>> m.check(np.array([90.0]), None, (), None)
    'degrees!'
    """

    key: str
    check: Check

    def __post_init__(self) -> None:
        if base_key(self.key) not in TITLES:
            raise ValueError(f"key: expected one of {sorted(TITLES)} (or 'KEY#variant'), got {self.key!r}")

    @property
    def title(self) -> str:
        """What the mistake is, for the instructor's summary."""
        return TITLES[base_key(self.key)]


def base_key(key: str) -> str:
    """The mistake a key names: ``"rotation_sense#sign"`` is a variant of ``"rotation_sense"``.

    A variant is one way of making the mistake (the axis's sign dropped, R_y's sines swapped): the feedback names
    a variant only where every failing case is that variant, and the class summary counts the mistake itself.

    >>> base_key("rotation_sense#sign"), base_key("degrees")
    ('rotation_sense', 'degrees')
    """
    return key.split("#", 1)[0]


def finite_floats(value: Any) -> np.ndarray | None:
    """``value`` as an array of floats, or None when it is not numbers or not all finite."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None
    return arr if np.all(np.isfinite(arr)) else None


def close(got: Any, ref: Any, tol: float = 1e-6) -> bool:
    """True when ``got`` equals ``ref`` within ``tol`` relative to the size of ``ref`` (shapes squeezed).

    >>> close([1.0, 2.0], np.array([1.0, 2.0 + 1e-9])), close([[1.0]], np.array(1.0)), close([1.0], [1.0, 2.0])
    (True, True, False)
    """
    a, b = finite_floats(got), finite_floats(ref)
    if a is None or b is None:
        return False
    if a.shape != b.shape:
        if a.size != b.size or np.squeeze(a).shape != np.squeeze(b).shape:
            return False
        a = a.reshape(b.shape)
    scale = max(1.0, float(np.max(np.abs(b)))) if b.size else 1.0
    return bool(b.size == 0 or np.max(np.abs(a - b)) <= tol * scale)

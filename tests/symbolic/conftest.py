"""Fixtures of the symbolic tests: the lecture's numeric lengths and derivations worth computing once."""

from __future__ import annotations

import pytest

from puma_course.symbolic import porter as PS


@pytest.fixture(scope="session")
def porter_lengths() -> tuple[float, float, float]:
    """(l1, l3, l4) of Porter's chain for numeric checks: unitless, l3 != l4 so that a mix-up shows."""
    return (1.0, 0.5, 0.3)


@pytest.fixture(scope="session")
def puma560_lengths() -> dict[str, float]:
    """The PUMA-560's lengths of the lecture's robot (metres), keyed like the symbols."""
    return {"a2": 0.4318, "a3": 0.0203, "d3": 0.15005, "d4": 0.4318}


@pytest.fixture(scope="session")
def mk3_lengths() -> dict[str, float]:
    """The MK3's lengths of Meghdari's table (millimetres), keyed like the symbols."""
    return {"d1": 360.0, "a1": 135.0, "a2": 250.0, "a3": 215.0, "d5": 100.0}


@pytest.fixture(scope="session")
def local_sc():
    """Porter's derived local product in ci, si, reduced modulo ci² + si² = 1 (about 1 s, so once)."""
    return PS.local_product().applyfunc(PS.to_sc).applyfunc(PS.reduce_sc)

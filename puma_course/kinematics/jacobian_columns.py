"""The geometric Jacobian's columns (:mod:`.jacobian`) for arrays the package built itself.

The formula of :func:`~.jacobian.jacobian_from_axes`, without its checks, and the same columns
written out from the frames of a DH chain's column walk. :mod:`.dh`, :mod:`.jacobian` and the
robots take them from here.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__: list[str] = []  # kernels for pre-validated arrays: the public face is .jacobian


def from_axes(z: np.ndarray, p: np.ndarray, e: np.ndarray, rev: np.ndarray) -> np.ndarray:
    """:func:`~.jacobian.jacobian_from_axes` for arrays the package built itself (nothing checked again)."""
    r = rev[:, None]
    Jv = np.where(r, np.cross(z, e[..., None, :] - p), z)
    Jw = np.where(r, z, 0.0)
    return np.concatenate([np.swapaxes(Jv, -1, -2), np.swapaxes(Jw, -1, -2)], axis=-2)


def walk_columns(F: list[tuple[Any, ...]], revolute: list[bool]) -> list[tuple[Any, ...]]:
    """Column i of J from the 12-number frames of the column walk (:func:`~.dh._walk`, frames 0..n).

    Frame i+1 holds joint i+1: its axis z (entries 2, 6, 10) and origin p (3, 7, 11); the reference
    point is the last frame's origin. The cross product is written out, as ``np.cross`` computes it:
    floats for one pose, (N,) arrays for a batch.
    """
    e = F[-1]
    ex, ey, ez = e[3], e[7], e[11]
    out = []
    for f, r in zip(F[1:], revolute, strict=True):
        zx, zy, zz = f[2], f[6], f[10]
        if r:
            dx, dy, dz = ex - f[3], ey - f[7], ez - f[11]
            out.append((zy * dz - zz * dy, zz * dx - zx * dz, zx * dy - zy * dx, zx, zy, zz))
        else:
            out.append((zx, zy, zz, 0.0, 0.0, 0.0))
    return out


def columns_to_array(cols: list[tuple[Any, ...]], batch: int | None) -> np.ndarray:
    """n columns of six entries as J (6, n), or (N, 6, n) when the entries are (N,) arrays."""
    if batch is None:
        return np.array(list(zip(*cols, strict=True)), dtype=float)
    J = np.zeros((batch, 6, len(cols)))
    for i, col in enumerate(cols):
        for k, value in enumerate(col):
            J[:, k, i] = value
    return J

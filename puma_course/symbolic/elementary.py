"""The one sympy API for elementary motions: rotations and translations as 4x4 homogeneous matrices.

Convention (the same as :mod:`puma_course.transforms`): a matrix maps coordinates in the moved
frame into the frame it moved from; rotations are active and right-handed. Products read left
to right as moving axes: ``rot("x", α) * trans("x", a)`` turns about x, then slides along the
*new* x (Meghdari's Rot(X, α) Trans(X, a); Porter's local-frame product).

* :func:`rot`, :func:`trans` - about / along the axis "x", "y" or "z" of the current frame;
* :func:`skew`, :func:`rot_about`, :func:`trans_along` - about / along any axis given as a vector,
  the line through a point (Rodrigues' formula; Porter's scene-frame motions R_a(α), T_a(l)).

Arguments may be symbols, expressions or exact numbers (``sp.pi / 2`` keeps cos/sin exact).

>>> t = sp.Symbol("t", real=True)
>>> sp.simplify(rot("z", t) * rot("z", -t)) == sp.eye(4)
True
"""

from __future__ import annotations

from typing import Any

import sympy as sp

__all__ = ["AXES", "rot", "trans", "skew", "rot_about", "trans_along"]

#: The axis names accepted by :func:`rot` and :func:`trans`.
AXES = ("x", "y", "z")


def _axis_index(axis: str) -> int:
    if not isinstance(axis, str) or axis not in AXES:
        raise ValueError(f"axis: expected one of 'x', 'y', 'z', got {axis!r}")
    return AXES.index(axis)


def rot(axis: str, angle: Any) -> sp.Matrix:
    """Rot(axis, angle): the 4x4 rotation about the frame's own axis "x", "y" or "z".

    Meghdari's Rot(X, α_{i-1}) and Rot(Z, θ_i); Porter's R_x, R_y, R_z of the local-frame
    product. Right-handed: ``rot("x", pi/2)`` turns y onto z.

    >>> rot("x", sp.pi / 2) * sp.Matrix([0, 1, 0, 1])  # y turns onto z
    Matrix([
    [0],
    [0],
    [1],
    [1]])
    >>> rot("y", sp.pi / 2)[:3, :3]  # z turns onto x
    Matrix([
    [ 0, 0, 1],
    [ 0, 1, 0],
    [-1, 0, 0]])
    """
    k = _axis_index(axis)
    C, S = sp.cos(sp.sympify(angle)), sp.sin(sp.sympify(angle))
    R = {
        0: [[1, 0, 0], [0, C, -S], [0, S, C]],
        1: [[C, 0, S], [0, 1, 0], [-S, 0, C]],
        2: [[C, -S, 0], [S, C, 0], [0, 0, 1]],
    }[k]
    M = sp.eye(4)
    M[:3, :3] = sp.Matrix(R)
    return M


def trans(axis: str, d: Any) -> sp.Matrix:
    """Trans(axis, d): the 4x4 translation by d along the frame's own axis "x", "y" or "z".

    Meghdari's Trans(X, a_{i-1}) and Trans(Z, d_i); Porter's T_x, T_z.

    >>> trans("x", sp.Symbol("a"))[:3, 3].T
    Matrix([[a, 0, 0]])
    >>> trans("z", 5) * sp.Matrix([1, 2, 3, 1])
    Matrix([
    [1],
    [2],
    [8],
    [1]])
    """
    M = sp.eye(4)
    M[_axis_index(axis), 3] = sp.sympify(d)
    return M


def _vector3(v: Any, name: str) -> sp.Matrix:
    m = sp.Matrix(v)
    if m.shape not in ((3, 1), (1, 3)):
        raise ValueError(f"{name}: expected 3 components, got shape {m.shape}")
    return m.reshape(3, 1)


def skew(v: Any) -> sp.Matrix:
    """[v]x, the 3x3 matrix with [v]x w = v x w (the cross-product matrix of Rodrigues' formula).

    >>> skew([1, 0, 0]) * sp.Matrix([0, 1, 0])  # x cross y = z
    Matrix([
    [0],
    [0],
    [1]])
    """
    x, y, z = _vector3(v, "v")
    return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def rot_about(a: Any, c: Any, s: Any, point: Any = None) -> sp.Matrix:
    """R_a(α): the 4x4 rotation by α about the line with unit direction ``a`` through ``point``.

    Rodrigues' formula K(a, α) = I + sin α [a]x + (1 - cos α) [a]x² for the rotation part, and
    the translation point - K point so that the line stays put (Porter's scene-frame R_a(α)).
    The angle is given by ``c`` = cos α and ``s`` = sin α, so that Porter's ci, si symbols keep
    the product a polynomial. ``a`` must be a unit vector (it is not normalised here); ``point``
    defaults to the origin.

    >>> t = sp.Symbol("t", real=True)
    >>> rot_about([0, 0, 1], sp.cos(t), sp.sin(t)) == rot("z", t)
    True
    >>> rot_about([0, 0, 1], 0, 1, point=[1, 0, 0]) * sp.Matrix([2, 0, 0, 1])  # quarter turn about x = 1
    Matrix([
    [1],
    [1],
    [0],
    [1]])
    """
    K = skew(a)
    R = sp.eye(3) + sp.sympify(s) * K + (1 - sp.sympify(c)) * K * K
    M = sp.eye(4)
    M[:3, :3] = R
    if point is not None:
        p = _vector3(point, "point")
        M[:3, 3] = p - R * p
    return M


def trans_along(a: Any, d: Any) -> sp.Matrix:
    """T_a(d): the 4x4 translation by d along the direction ``a`` (a unit vector; Porter's scene-frame T_a(l)).

    >>> trans_along([0, 1, 0], sp.Symbol("l"))[:3, 3].T
    Matrix([[0, l, 0]])
    """
    M = sp.eye(4)
    M[:3, 3] = sp.sympify(d) * _vector3(a, "a")
    return M

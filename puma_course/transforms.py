"""Rotations, Rodrigues' formula K(a, θ) and homogeneous transforms.

Conventions (stated once for the whole course):

* Angles are in radians.
* Rotations are *active*: ``R @ v`` turns the vector ``v``.
* A 4x4 transform ``T`` maps coordinates of a child frame into its parent
  frame: ``p_parent = T @ [p_child, 1]``.
* Batches put the batch axis first: angles of shape (N,) give (N, 3, 3).
* Composing about the *fixed* (scene) frame multiplies on the left,
  composing about the *moving* (local) frame multiplies on the right;
  :func:`compose_fixed` and :func:`compose_moving` spell both orders out.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ._validate import MAX_MAGNITUDE, as_angle, as_array, as_rotation, as_tol, as_transform, check_broadcast

__all__ = [
    "rotx",
    "roty",
    "rotz",
    "skew",
    "rodrigues",
    "axis_angle",
    "homogeneous",
    "transl",
    "transx",
    "transy",
    "transz",
    "trotx",
    "troty",
    "trotz",
    "trot",
    "inverse_transform",
    "compose_fixed",
    "compose_moving",
    "is_rotation",
    "wrap_angle",
]


def _rot(angle: Any, axis: int, name: str = "angle") -> np.ndarray:
    t = as_angle(angle, name)
    c, s = np.cos(t), np.sin(t)
    R = np.zeros(t.shape + (3, 3))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    R[..., axis, axis] = 1.0
    R[..., i, i] = c
    R[..., j, j] = c
    R[..., i, j] = -s
    R[..., j, i] = s
    return R


def rotx(angle: Any) -> np.ndarray:
    """Rotation about the x axis by ``angle`` (radians); (3, 3), or (N, 3, 3) for N angles.

    >>> np.round(rotx(np.pi / 2) @ [0, 1, 0], 12)
    array([0., 0., 1.])
    """
    return _rot(angle, 0)


def roty(angle: Any) -> np.ndarray:
    """Rotation about the y axis by ``angle`` (radians).

    >>> np.round(roty(np.pi / 2) @ [0, 0, 1], 12)
    array([1., 0., 0.])
    """
    return _rot(angle, 1)


def rotz(angle: Any) -> np.ndarray:
    """Rotation about the z axis by ``angle`` (radians).

    >>> np.round(rotz(np.pi / 2) @ [1, 0, 0], 12)
    array([0., 1., 0.])
    """
    return _rot(angle, 2)


def skew(v: Any) -> np.ndarray:
    """The cross-product matrix [v]x, so that ``skew(v) @ w == np.cross(v, w)``.

    >>> skew([1, 2, 3]) @ [4, 5, 6]
    array([-3.,  6., -3.])
    """
    v = as_array(v, "v", (3,), batch=True)
    S = np.zeros(v.shape[:-1] + (3, 3))
    S[..., 0, 1], S[..., 0, 2] = -v[..., 2], v[..., 1]
    S[..., 1, 0], S[..., 1, 2] = v[..., 2], -v[..., 0]
    S[..., 2, 0], S[..., 2, 1] = -v[..., 1], v[..., 0]
    return S


def rodrigues(axis: Any, angle: Any) -> np.ndarray:
    """Rodrigues' rotation K(a, θ) about ``axis`` by ``angle`` (right-hand rule).

    K(a, θ) = I + sin θ [k]x + (1 - cos θ) [k]x², with k = a / |a|. Any
    non-zero axis is accepted (it is normalised here). ``axis`` (3,) or
    (N, 3) and ``angle`` scalar or (N,) broadcast to a batch (N, 3, 3).

    >>> np.allclose(rodrigues([0, 0, 2], 0.3), rotz(0.3))
    True
    """
    a = as_array(axis, "axis", (3,), batch=True)
    t = as_angle(angle)
    check_broadcast(axis=a.shape[:-1], angle=np.shape(t))  # not numpy's "could not be broadcast" (issue 21)
    # scaled by its largest entry before squaring (issue 21: [1e200, 0, 0] squared to inf gave the identity)
    big = np.max(np.abs(a), axis=-1, keepdims=True)
    if np.any(big == 0.0):
        raise ValueError("axis: expected a non-zero 3-vector (the rotation axis), got a zero vector")
    a = a / big
    k = a / np.sqrt(a[..., 0:1] ** 2 + a[..., 1:2] ** 2 + a[..., 2:3] ** 2)
    K = skew(k)
    s = np.sin(t)[..., None, None]
    c = np.cos(t)[..., None, None]
    # [k]x² = k kᵀ - I, elementwise (no `@`: a BLAS kernel would decide the last bit)
    return c * np.eye(3) + s * K + (1.0 - c) * (k[..., :, None] * k[..., None, :])


def axis_angle(R: Any) -> tuple[np.ndarray, Any]:
    """Axis and angle of a rotation: ``rodrigues(*axis_angle(R)) == R``.

    Returns a unit axis and an angle in [0, π]. For the identity (angle 0) the
    axis is arbitrary and e_z is returned; for a half turn (angle π) the axis
    is found from R + I (its sign is then immaterial). A batch R (N, 3, 3)
    gives axes (N, 3) and angles (N,), in one vectorised pass.

    >>> axis, angle = axis_angle(rotx(0.5))
    >>> np.round(axis, 12), round(angle, 12)
    (array([1., 0., 0.]), 0.5)
    """
    R = as_rotation(R, "R", batch=True)
    cos_t = np.clip((np.trace(R, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    w = np.stack([R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]], axis=-1)
    sin_t = np.linalg.norm(w, axis=-1) / 2.0
    angle = np.arctan2(sin_t, cos_t)
    # Below a quarter turn the antisymmetric part w = 2 sin(θ) k gives k to eps / sin θ, even for tiny θ;
    # above it the symmetric part gives k to eps / (1 - cos θ) <= eps (w's eps / sin θ grows towards π).
    from_w = (sin_t > 0.0) & (cos_t > 0.0)
    k_w = w / np.where(from_w, 2.0 * sin_t, 1.0)[..., None]
    # (near) half turn: the symmetric part (R + R^T)/2 - cos θ I = (1 - cos θ) k k^T exactly (R + I would
    # keep sin θ [k]x, off by 5e-7 at θ = π - 1e-6, issue 21); take its largest column, signed like w.
    B = (R + np.swapaxes(R, -1, -2)) / 2.0 - cos_t[..., None, None] * np.eye(3)
    col = np.argmax(np.diagonal(B, axis1=-2, axis2=-1), axis=-1)
    k_b = np.take_along_axis(B, col[..., None, None], axis=-1)[..., 0]
    k_b = k_b / np.maximum(np.linalg.norm(k_b, axis=-1, keepdims=True), 1e-300)
    k_b = np.where((np.sum(k_b * w, axis=-1) < 0)[..., None], -k_b, k_b)
    identity = ~from_w & (cos_t > 0)  # exactly the identity: any axis will do
    k = np.where(from_w[..., None], k_w, np.where(identity[..., None], np.array([0.0, 0.0, 1.0]), k_b))
    if R.ndim == 2:
        return k, float(angle)
    return k, angle


def homogeneous(R: Any, p: Any) -> np.ndarray:
    """The 4x4 transform [[R, p], [0, 1]]; R (3, 3) or (N, 3, 3), p (3,) or (N, 3).

    ``R`` must be a rotation (orthonormal, det +1): anything else would make a "transform"
    that is not rigid, and :func:`inverse_transform` and every frame built on it would be wrong.

    >>> homogeneous(np.eye(3), [1, 2, 3])[:3, 3]
    array([1., 2., 3.])
    """
    R = as_rotation(R, "R", batch=True)
    p = as_array(p, "p", (3,), batch=True, max_magnitude=MAX_MAGNITUDE)
    try:
        batch = np.broadcast_shapes(R.shape[:-2], p.shape[:-1])
    except ValueError:
        raise ValueError(f"R, p: expected batches of the same length, got shapes {R.shape} and {p.shape}") from None
    T = np.zeros(batch + (4, 4))
    T[..., :3, :3] = R
    T[..., :3, 3] = p
    T[..., 3, 3] = 1.0
    return T


def transl(p: Any) -> np.ndarray:
    """Pure translation by the vector ``p``: Trans(p) as a 4x4 transform.

    >>> transl([1, 0, 0]) @ [0, 0, 0, 1]
    array([1., 0., 0., 1.])
    """
    p = as_array(p, "p", (3,), batch=True, max_magnitude=MAX_MAGNITUDE)
    return homogeneous(np.broadcast_to(np.eye(3), p.shape[:-1] + (3, 3)), p)


def _trans_axis(d: Any, axis: int) -> np.ndarray:
    d = as_array(d, "d", what="a distance (a number, or an array of shape (N,))", max_magnitude=MAX_MAGNITUDE)
    if d.ndim > 1:
        raise ValueError(f"d: expected a number or an array of shape (N,), got an array of shape {d.shape}")
    p = np.zeros(d.shape + (3,))
    p[..., axis] = d
    return transl(p)


def transx(d: Any) -> np.ndarray:
    """Trans(X, d): translation along x by ``d`` (a 4x4; d of shape (N,) gives (N, 4, 4)).

    >>> transx(2.0) @ [0, 0, 0, 1]
    array([2., 0., 0., 1.])
    """
    return _trans_axis(d, 0)


def transy(d: Any) -> np.ndarray:
    """Trans(Y, d): translation along y by ``d``.

    >>> transy(-1.0)[:3, 3]
    array([ 0., -1.,  0.])
    """
    return _trans_axis(d, 1)


def transz(d: Any) -> np.ndarray:
    """Trans(Z, d): translation along z by ``d``.

    >>> transz([1.0, 2.0])[:, 2, 3]
    array([1., 2.])
    """
    return _trans_axis(d, 2)


def trotx(angle: Any) -> np.ndarray:
    """Rot(X, angle) as a 4x4 transform (no translation).

    >>> np.round(trotx(np.pi / 2) @ [0, 1, 0, 1], 12) + 0.0
    array([0., 0., 1., 1.])
    """
    R = rotx(angle)
    return homogeneous(R, np.zeros(R.shape[:-2] + (3,)))


def troty(angle: Any) -> np.ndarray:
    """Rot(Y, angle) as a 4x4 transform (no translation).

    >>> np.round(troty(np.pi / 2) @ [0, 0, 1, 1], 12) + 0.0
    array([1., 0., 0., 1.])
    """
    R = roty(angle)
    return homogeneous(R, np.zeros(R.shape[:-2] + (3,)))


def trotz(angle: Any) -> np.ndarray:
    """Rot(Z, angle) as a 4x4 transform (no translation).

    >>> np.round(trotz(np.pi / 2) @ [1, 0, 0, 1], 12) + 0.0
    array([0., 1., 0., 1.])
    """
    R = rotz(angle)
    return homogeneous(R, np.zeros(R.shape[:-2] + (3,)))


def trot(axis: Any, angle: Any, point: Any = (0.0, 0.0, 0.0)) -> np.ndarray:
    """Rotation by ``angle`` about the line through ``point`` along ``axis``, as a 4x4.

    This is Porter's R_a(α) for an axis that does not pass through the origin:
    T = Trans(point) K(a, α) Trans(-point).

    >>> np.round(trot([0, 0, 1], np.pi, point=[1, 0, 0]) @ [0, 0, 0, 1], 12) + 0.0
    array([2., 0., 0., 1.])
    """
    R = rodrigues(axis, angle)
    c = as_array(point, "point", (3,), batch=True, max_magnitude=MAX_MAGNITUDE)
    check_broadcast(**{"axis, angle": R.shape[:-2], "point": c.shape[:-1]})
    p = c - np.einsum("...ij,...j->...i", R, c)
    return homogeneous(R, p)


def inverse_transform(T: Any) -> np.ndarray:
    """Inverse of a rigid transform, [[R^T, -R^T p], [0, 1]], for (4, 4) or (N, 4, 4).

    >>> T = homogeneous(rotz(0.4), [1, 2, 3])
    >>> np.allclose(inverse_transform(T) @ T, np.eye(4))
    True

    The formula holds only for a rigid transform, so ``T`` is checked as one
    (last row 0 0 0 1, orthonormal rotation part); anything else raises ``ValueError``.
    """
    T = as_transform(T, "T", batch=True)
    Rt = np.swapaxes(T[..., :3, :3], -1, -2)
    return homogeneous(Rt, -np.einsum("...ij,...j->...i", Rt, T[..., :3, 3]))


def compose_moving(*transforms: Any) -> np.ndarray:
    """Compose motions each given in the *moving* (local) frame: T1 @ T2 @ ... @ Tn.

    "First T1, then T2 about the axes that T1 produced, ..." multiplies on the
    right. Porter's local-frame product Rz(α1) Tz(l1) Ry(α2) ... is this order.

    Turn 90° about x, then 90° about the *new* z (the old -y): e_y ends at -e_x.

    >>> np.round(compose_moving(trotx(np.pi / 2), trotz(np.pi / 2)) @ [0, 1, 0, 0], 12) + 0.0
    array([-1.,  0.,  0.,  0.])
    """
    if not transforms:
        raise ValueError("transforms: expected at least one transform, got none")
    checked = [as_transform(T, f"transforms[{k}]", batch=True) for k, T in enumerate(transforms)]
    check_broadcast(**{f"transforms[{k}]": T.shape[:-2] for k, T in enumerate(checked)})
    out = checked[0]
    for T in checked[1:]:
        out = out @ T
    return out


def compose_fixed(*transforms: Any) -> np.ndarray:
    """Compose motions each given in the *fixed* (scene) frame: Tn @ ... @ T2 @ T1.

    "First T1, then T2 about the scene axes, ..." multiplies on the left, so the
    same list of motions gives the reverse product of :func:`compose_moving`
    when each later motion is re-expressed about the fixed axes.

    Turn 90° about x (e_y goes to e_z), then 90° about the fixed z (e_z stays):

    >>> np.round(compose_fixed(trotx(np.pi / 2), trotz(np.pi / 2)) @ [0, 1, 0, 0], 12) + 0.0
    array([0., 0., 1., 0.])
    """
    if not transforms:
        raise ValueError("transforms: expected at least one transform, got none")
    checked = [as_transform(T, f"transforms[{k}]", batch=True) for k, T in enumerate(transforms)]
    check_broadcast(**{f"transforms[{k}]": T.shape[:-2] for k, T in enumerate(checked)})
    out = checked[-1]
    for T in checked[-2::-1]:
        out = out @ T
    return out


def is_rotation(R: Any, tol: float = 1e-9) -> bool:
    """True when ``R`` is a 3x3 (or batch of) orthonormal matrix with det +1.

    >>> is_rotation(rotz(0.3)), is_rotation(np.diag([1.0, 1.0, -1.0]))
    (True, False)
    """
    # a NaN tolerance made every comparison pass (issue 21); below 1e-12 a product of twenty rotations
    # (R^T R off I by up to 4e-15) would be called "not a rotation": float64 cannot honour that
    tol = as_tol(tol, "tol", upper=1.0, lower=1e-12)
    try:
        as_rotation(R, "R", batch=True, tol=tol)
    except ValueError:
        return False
    return True


_PI = math.pi
_TWO_PI = 2.0 * math.pi


def wrap_angle(angle: Any) -> Any:
    """Angles wrapped to (-π, π]: the package's one wrapping rule (joint angles, joint distances).

    A Python float gives a float (the hot scalar paths of the solvers), anything else an array.
    Input is validated like every angle (``ValueError`` naming ``angle``), except that a float64 array
    (the solvers' own batches, where NaN marks "no solution") passes unchecked but for infinity.

    >>> wrap_angle([np.pi, -np.pi, 3 * np.pi / 2]) / np.pi
    array([ 1. ,  1. , -0.5])
    >>> wrap_angle(-math.pi), wrap_angle(3 * math.pi)  # -π and 3π are π: the interval is open at -π
    (3.141592653589793, 3.141592653589793)
    """
    if isinstance(angle, float):
        if angle - angle != 0.0:  # NaN or infinity (issue 21: NaN came back)
            raise ValueError(f"angle: expected finite angles in radians, got {angle!r}")
        w = _PI - (_PI - angle) % _TWO_PI
        return w + _TWO_PI if w <= -_PI else w  # rounding may land on -π itself
    if type(angle) is np.ndarray and angle.dtype == np.float64:  # the solvers' batches: NaN marks no solution
        if np.isinf(angle).any():
            raise ValueError("angle: expected finite angles in radians, got infinity")
        a = angle
    else:  # None, text, booleans, complex, objects, ragged lists, NaN: refused (issue 21)
        a = as_array(angle, "angle", what="angles in radians (numbers)")
    wa = _PI - np.mod(_PI - a, _TWO_PI)
    return np.where(wa <= -_PI, wa + _TWO_PI, wa)

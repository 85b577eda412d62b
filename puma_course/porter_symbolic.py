"""Symbolic (sympy) derivations and checks for Porter's chain (lectures 05-07).

Imports sympy at import time: never imported by ``puma_course`` itself. Everything here
is an independent second derivation of what :mod:`puma_course.porter` computes numerically.

* :func:`local_product` - the corrected local-frame product F05 (moving axes);
* :func:`printed_local_product` - the product exactly as printed (no ``Tx(q2)``);
* :func:`scene_product` - the scene-frame product, each motion about/along the current axis
  expressed in the scene frame, built with Rodrigues' formula about a line;
* :func:`printed_closed_forms` / :func:`closed_forms` / :func:`compare_closed_forms` - the printed
  x5, y5, z5, p5 (transcribed with their damage) against the derived ones;
* :func:`printed_ver1` - Porter's eqs. 8-16 as printed, as sympy expressions of the pose.
"""

from __future__ import annotations

import sympy as sp

__all__ = [
    "SYMBOLS",
    "rot",
    "trans",
    "local_product",
    "printed_local_product",
    "scene_product",
    "closed_forms",
    "printed_closed_forms",
    "to_sc",
    "reduce_sc",
    "sc_values",
    "corrected_z5_2",
    "compare_closed_forms",
    "printed_ver1",
    "pose_symbols",
]

a1, a2, q2, a3, a4, a5 = sp.symbols("alpha1 alpha2 q2 alpha3 alpha4 alpha5", real=True)
l1, l3, l4 = sp.symbols("l1 l3 l4", positive=True)
SYMBOLS = {"alpha1": a1, "alpha2": a2, "q2": q2, "alpha3": a3, "alpha4": a4, "alpha5": a5, "l1": l1, "l3": l3, "l4": l4}
Q = (a1, a2, q2, a3, a4, a5)
c = {i: sp.Symbol(f"c{i}") for i in range(1, 6)}
s = {i: sp.Symbol(f"s{i}") for i in range(1, 6)}


def rot(axis: str, t: sp.Expr) -> sp.Matrix:
    """4x4 rotation about the local axis 'x', 'y' or 'z' by t (sympy; maps the turned frame into the old one).

    >>> rot("z", sp.pi / 2)[:3, :3]
    Matrix([
    [0, -1, 0],
    [1,  0, 0],
    [0,  0, 1]])
    """
    C, S = sp.cos(t), sp.sin(t)
    R = {
        "x": [[1, 0, 0], [0, C, -S], [0, S, C]],
        "y": [[C, 0, S], [0, 1, 0], [-S, 0, C]],
        "z": [[C, -S, 0], [S, C, 0], [0, 0, 1]],
    }[axis]
    M = sp.eye(4)
    M[:3, :3] = sp.Matrix(R)
    return M


def trans(axis: str, d: sp.Expr) -> sp.Matrix:
    """4x4 translation along the local axis 'x', 'y' or 'z' by d (sympy).

    >>> trans("x", l4)[:3, 3].T
    Matrix([[l4, 0, 0]])
    """
    M = sp.eye(4)
    M["xyz".index(axis), 3] = d
    return M


# the motions in chain order: (kind, axis, value); kind R = rotation, T = translation
MOTIONS = [("R", "z", a1), ("T", "z", l1), ("R", "y", a2), ("T", "x", q2), ("R", "y", a3), ("T", "z", -l3),
           ("R", "z", a4), ("T", "x", l4), ("R", "x", a5)]  # fmt: skip


def local_product() -> sp.Matrix:
    """F05 = Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) Rz(α4) Tx(l4) Rx(α5) (corrected).

    Moving axes: each factor acts about/along an axis of the frame reached so far (Porter's
    local-frame product, with the ``Tx(q2)`` the print omits). Height of p5 at the zero pose:

    >>> F = local_product()
    >>> F[2, 3].subs({a1: 0, a2: 0, a3: 0, a4: 0, q2: 1})
    l1 - l3
    """
    M = sp.eye(4)
    for kind, axis, v in MOTIONS:
        M = M * (rot(axis, v) if kind == "R" else trans(axis, v))
    return M


def printed_local_product() -> sp.Matrix:
    """The local product as printed: Rz(α1) Tz(l1) Ry(α2) Ry(α3) Tz(-l3) Rz(α4) Tx(l4) Rx(α5) (no Tx(q2)).

    Without ``Tx(q2)`` the prismatic joint cannot move the hand:

    >>> printed_local_product().has(q2), local_product().has(q2)
    (False, True)
    """
    M = sp.eye(4)
    for kind, axis, v in MOTIONS:
        if v is q2:
            continue
        M = M * (rot(axis, v) if kind == "R" else trans(axis, v))
    return M


_ANGLE_INDEX = {a1: 1, a2: 2, a3: 3, a4: 4, a5: 5}


def reduce_sc(expr: sp.Expr) -> sp.Expr:
    """Expand and reduce a polynomial in ci, si modulo ci² + si² = 1 (a canonical form: ci of degree <= 1).

    >>> reduce_sc(c[1] ** 2 + s[1] ** 2)
    1
    >>> reduce_sc(c[2] ** 3)
    -c2*s2**2 + c2
    """
    e = sp.expand(expr)
    for i in range(1, 6):
        if e.has(c[i]):
            e = sp.expand(sp.rem(sp.Poly(e, c[i]), sp.Poly(c[i] ** 2 + s[i] ** 2 - 1, c[i])).as_expr())
    return e


def scene_product(lines: str = "current") -> sp.Matrix:
    """The scene-frame product R_x4(α5) T_x4(l4) ... T_z1(l1) R_z0(α1), in ci, si (reduced).

    Each motion acts about/along an axis given in SCENE coordinates: the unit axis is the
    column of the frame reached so far, and each step, a Rodrigues rotation
    K(a, α) = I + sα [a]x + (1 - cα) [a]x² about a line (point c: translation c - K c) or a
    translation l a, multiplies the product on the LEFT. Nothing of the local product is used.
    ``lines="current"``: the rotation lines pass through the current joint point (p2 for α2,
    p3 for α3), the reading that matches the printed p5. ``lines="literal"``: y1 and y2 taken
    as lines through the origins p1 = p0 and p2, as the subscripts read literally.

    The scene-frame product equals the local product (about 1 s):

    >>> M = scene_product()
    >>> sp.expand(M[2, 3] - closed_forms()["p5"][2])
    0
    """
    F = sp.eye(4)  # the frame reached so far (its columns: the axes and the point, in the scene)
    M = sp.eye(4)  # the accumulated scene-frame product
    p2 = None
    for k, (kind, axis, v) in enumerate(MOTIONS):
        a = F[:3, "xyz".index(axis)]
        point = F[:3, 3]
        if lines == "literal" and k == 2:
            point = sp.zeros(3, 1)  # y1 through p1 = p0
        if lines == "literal" and k == 4:
            point = p2  # y2 through p2
        step = sp.eye(4)
        if kind == "R":
            i = _ANGLE_INDEX[v]
            K = sp.Matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
            R = sp.eye(3) + s[i] * K + (1 - c[i]) * K * K
            step[:3, :3] = R
            step[:3, 3] = point - R * point
        else:
            step[:3, 3] = v * a
        M = (step * M).applyfunc(reduce_sc)
        F = (step * F).applyfunc(reduce_sc)
        if k == 1:
            p2 = F[:3, 3]
    return M


def sc_values(q, l1_: float, l3_: float, l4_: float) -> dict:
    """Substitution dict {ci: cos αi, si: sin αi, q2, l1, l3, l4} for a numeric configuration q.

    q = (α1, α2, q2, α3, α4, α5) in radians (the order of :mod:`puma_course.porter`).

    >>> d = sc_values([0.0, 0.0, 2.0, 0.0, 0.0, 0.0], 1.0, 0.5, 0.3)
    >>> d[c[1]], d[s[1]], d[q2], d[l3]
    (1.0, 0.0, 2.0, 0.5)
    >>> float(closed_forms()["p5"][0].subs(d))  # q2 + l4 at the zero angles
    2.3
    """
    import math

    angles = dict(zip((1, 2, 3, 4, 5), (q[0], q[1], q[3], q[4], q[5]), strict=True))
    d = {c[i]: math.cos(float(t)) for i, t in angles.items()}
    d.update({s[i]: math.sin(float(t)) for i, t in angles.items()})
    d.update({q2: float(q[2]), l1: l1_, l3: l3_, l4: l4_})
    return d


def to_sc(expr: sp.Expr) -> sp.Expr:
    """Rewrite cos(αi), sin(αi) as the symbols ci, si (Porter's notation) and expand.

    >>> to_sc(sp.cos(a1 + a2))
    c1*c2 - s1*s2
    """
    rep = {}
    for i, t in zip((1, 2, 3, 4, 5), (a1, a2, a3, a4, a5), strict=True):
        rep[sp.cos(t)] = c[i]
        rep[sp.sin(t)] = s[i]
    return sp.expand(sp.expand_trig(expr).subs(rep))


def closed_forms() -> dict[str, list[sp.Expr]]:
    """x5, y5, z5, p5 (the columns of the derived F05) in Porter's ci, si notation, expanded.

    >>> closed_forms()["x5"][2]
    -c2*c4*s3 - c3*c4*s2
    """
    M = local_product()
    return {name: [to_sc(M[i, j]) for i in range(3)] for j, name in enumerate(("x5", "y5", "z5", "p5"))}


def printed_closed_forms() -> dict[str, list[sp.Expr]]:
    """x5, y5, z5, p5 transcribed exactly as printed, including the damaged z5[1] ('-s2(..) + s2(..)').

    >>> printed_closed_forms()["z5"][1]
    -c1*c4*s5 + s2*(c3*c5 - s3*s4*s5) - s2*(c3*s4*s5 + c5*s3)
    """
    c1, c2, c3, c4, c5 = (c[i] for i in range(1, 6))
    s1, s2, s3, s4, s5 = (s[i] for i in range(1, 6))
    A = q2 - s3 * l3 + c3 * c4 * l4
    B = c3 * l3 + s3 * c4 * l4
    return {
        "x5": [
            c1 * c4 * (c2 * c3 - s2 * s3) - s1 * s4,
            s1 * c4 * (c2 * c3 - s2 * s3) + c1 * s4,
            -c4 * (s2 * c3 + c2 * s3),
        ],
        "y5": [
            c1 * (c2 * (s3 * s5 - c3 * s4 * c5) + s2 * (c3 * s5 + s3 * s4 * c5)) - s1 * c4 * c5,
            s1 * (c2 * (s3 * s5 - c3 * s4 * c5) + s2 * (c3 * s5 + s3 * s4 * c5)) + c1 * c4 * c5,
            -s2 * (s3 * s5 - c3 * s4 * c5) + c2 * (c3 * s5 + s3 * s4 * c5),
        ],
        "z5": [
            c1 * (c2 * (s3 * c5 + c3 * s4 * s5) + s2 * (c3 * c5 - s3 * s4 * s5)) + s1 * c4 * s5,
            -s2 * (s3 * c5 + c3 * s4 * s5) + s2 * (c3 * c5 - s3 * s4 * s5) - c1 * c4 * s5,  # as printed (damaged)
            -s2 * (s3 * c5 + c3 * s4 * s5) + c2 * (c3 * c5 - s3 * s4 * s5),
        ],
        "p5": [c1 * (c2 * A - s2 * B) - s1 * s4 * l4, s1 * (c2 * A - s2 * B) + c1 * s4 * l4, -s2 * A - c2 * B + l1],
    }


def corrected_z5_2() -> sp.Expr:
    """The second component of z5 following the pattern of y5[1]: s1(c2(..) + s2(..)) - c1 c4 s5.

    It agrees with the derived product, the printed entry does not:

    >>> derived = closed_forms()["z5"][1]
    >>> sp.expand(corrected_z5_2() - derived), sp.expand(printed_closed_forms()["z5"][1] - derived) == 0
    (0, False)
    """
    c1, c2, c3, c4, c5 = (c[i] for i in range(1, 6))
    s1, s2, s3, s4, s5 = (s[i] for i in range(1, 6))
    return s1 * (c2 * (s3 * c5 + c3 * s4 * s5) + s2 * (c3 * c5 - s3 * s4 * s5)) - c1 * c4 * s5


def compare_closed_forms() -> dict[str, bool]:
    """``{"x5[0]": True, ..., "z5[1]": False, ...}``: whether each printed entry equals the derived one.

    >>> [k for k, ok in compare_closed_forms().items() if not ok]
    ['z5[1]']
    """
    derived, printed = closed_forms(), printed_closed_forms()
    out = {}
    for name in ("x5", "y5", "z5", "p5"):
        for i in range(3):
            out[f"{name}[{i}]"] = sp.expand(derived[name][i] - printed[name][i]) == 0
    return out


def pose_symbols() -> dict[str, sp.Symbol]:
    """Symbols x5_1..p5_3 (Porter's x_{5,1} etc.) for the entries of the given pose.

    >>> P = pose_symbols()
    >>> len(P), P["p5_3"]
    (12, p5_3)
    """
    return {f"{v}5_{i}": sp.Symbol(f"{v}5_{i}") for v in "xyzp" for i in (1, 2, 3)}


def printed_ver1() -> dict[str, sp.Expr]:
    """Porter's Ver.1 formulas as printed (right-hand sides), in the pose symbols and c1, s1, c2, c4, s4.

    Keys: ``s4_eq8``, ``s4_eq8_p`` (the second form, with p5), ``tan_a1_eq9``, ``c5_eq11``,
    ``s5_eq11``, ``a5_eq12``, ``a6_eq12``, ``tan_a2_eq14``, ``q2_eq15``.

    >>> printed_ver1()["s4_eq8"]
    c1*x5_2 - s1*x5_1
    """
    P = pose_symbols()
    x51, x52, x53 = P["x5_1"], P["x5_2"], P["x5_3"]
    y51, y52 = P["y5_1"], P["y5_2"]
    z51, z52 = P["z5_1"], P["z5_2"]
    p51, p52, p53 = P["p5_1"], P["p5_2"], P["p5_3"]
    c1, s1, c2, c4, s4 = c[1], s[1], c[2], c[4], s[4]
    return {
        "s4_eq8": c1 * x52 - s1 * x51,
        "s4_eq8_p": (c1 * p52 - s1 * p51) / l4,
        "tan_a1_eq9": (p52 - l4 * x52) / (p51 - l4 * x51),
        "c5_eq11": (c1 * y52 - s1 * y51) / c4,
        "s5_eq11": (s1 * z51 - c1 * z52) / c4,
        "a5_eq12": (x51 + s1 * s4) / (c1 * c4),
        "a6_eq12": -x53 / c4,
        "tan_a2_eq14": -(c1 * c4 * (p53 - l4 * x53 - l1) + l3 * (x51 + s1 * s4))
        / (c4 * (p51 - l4 * x51) - c1 * l3 * x53),
        "q2_eq15": (c4 * (p51 - l4 * x51) - c1 * l3 * x53) / (c1 * c2 * c4),
    }

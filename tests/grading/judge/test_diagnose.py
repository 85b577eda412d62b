"""Feedback that names the mistake: each diagnosed mistake, crafted by hand, is recognised and worded.

Every test builds the wrong answer a student would write (a transposed matrix, degrees, the standard-DH
link matrix, the factors in reverse order, ...) with numpy, hands it to the real question's judge, and
checks the verdict's key and message. The right answer passes; an answer with no recognisable mistake gets
the generic reason, not a made-up diagnosis.
"""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.grading import EXERCISES
from puma_course.grading.judge.diagnose import TITLES, Mistake, base_key, close, diagnose, matches
from puma_course.grading.judge.verdict import Verdict


def judge(name, qid, got, *args):
    """The verdict of question ``name:qid`` on ``got`` for the arguments ``args``."""
    q = EXERCISES[name].question(qid)
    expected = q.reference(*args)
    if not callable(expected) and not isinstance(expected, dict):
        expected = np.asarray(expected, dtype=float)
    return q.judge(got, expected, args)


def right(name, qid, *args):
    return np.asarray(EXERCISES[name].question(qid).right_answer(*args), dtype=float)


def assert_named(verdict: Verdict, key: str, *words: str) -> None:
    assert not verdict.passed and verdict.mistake == key, verdict
    for word in words:
        assert word in verdict.reason, (word, verdict.reason)


def rot(axis, t):
    c, s = np.cos(t), np.sin(t)
    return {
        "x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
        "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
        "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]),
    }[axis]


def rot_about(a, t):
    """Rodrigues' formula written out: the turn by t about the unit axis a."""
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(t) * k + (1 - np.cos(t)) * k @ k


def homogeneous(R, p):
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T


def skew(k):
    return np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])


# ------------------------------------------------------------------------------------------ rotations (ex01)
def test_a_turn_the_wrong_way_and_a_transposed_rotation():
    # ex01 q1: about "-y" the transpose of the answer is R_y(+θ), the axis's sign left out (or R_y's sines swapped)
    assert judge("ex01_rotations", "q1", rot("y", -0.7), "-y", 0.7).passed
    assert_named(judge("ex01_rotations", "q1", rot("y", 0.7), "-y", 0.7), "rotation_sense", "not about -y", "sign")
    assert_named(judge("ex01_rotations", "q1", rot("y", -0.7), "y", 0.7), "rotation_sense", "R_y's sines are swapped")
    assert_named(judge("ex01_rotations", "q1", rot("z", 0.7).T, "z", 0.7), "rotation_sense", "wrong way")
    assert_named(judge("ex01_rotations", "q1", rot("x", 0.7), "-x", 0.7), "rotation_sense", '"-e" is a turn about e')
    # the general message speaks of any signed axis: on a "-z" case it does not explain with "-x"
    about_minus_z = judge("ex01_rotations", "q1", rot("z", 0.7), "-z", 0.7)
    assert_named(about_minus_z, "rotation_sense", '"-e" is a turn about e by -θ', "about z, x towards y")
    assert "-x" not in about_minus_z.reason and '"x"' not in about_minus_z.reason, about_minus_z.reason
    # ex01 q2: the turn carrying v onto u is the transpose of the one asked for
    u, v = np.array([0.0, 1.0, 1.0]), np.array([0.5, -1.0, -0.2])
    R = right("ex01_rotations", "q2", u, v)
    assert np.allclose(R @ u / np.linalg.norm(u), v / np.linalg.norm(v))
    assert_named(judge("ex01_rotations", "q2", R.T, u, v), "transposed", "carries v onto u")


def test_degrees_where_radians_were_expected():
    # an angle argument taken as degrees: np.cos(np.radians(angle))
    assert_named(judge("ex01_rotations", "q1", rot("y", np.radians(1.2)), "y", 1.2), "degrees", "degrees")
    assert_named(judge("ex01_rotations", "q1", rot("y", -np.radians(1.2)), "-y", 1.2), "degrees", "degrees")
    # an angle returned in degrees: a quarter turn about z applied to R_x(0.5), by 1 rad
    R_a = rot("x", 0.5)
    assert_named(
        judge("ex01_rotations", "q3", [0, 0, 1, np.degrees(1.0)], R_a, rot("z", 1.0) @ R_a), "degrees", "radians"
    )
    T_prev = homogeneous(rot("z", 0.5), [0.1, 0.2, 0.3])
    T = T_prev @ link(np.pi / 2, 0.4, -1.0, 0.15)
    assert_named(judge("ex02_dh_frames", "q1", [90.0, 0.4, np.degrees(-1.0), 0.15], T_prev, T), "degrees")
    wrong = link(np.radians(0.7), 0.4, np.radians(-1.0), 0.15)  # q2: the angles taken as degrees
    assert_named(judge("ex02_dh_frames", "q2", np.linalg.inv(wrong), 0.7, 0.4, -1.0, 0.15), "degrees", "radians")


def test_an_axis_not_normalised():
    # ex01 q2: u = (2, 0, 0), v = (0, 3, 0): a quarter turn about e_z, but u × v = (0, 0, 6) used as it is
    u, v, t = np.array([2.0, 0.0, 0.0]), np.array([0.0, 3.0, 0.0]), np.pi / 2
    a = np.cross(u, v)
    raw = np.eye(3) + np.sin(t) * skew(a) + (1 - np.cos(t)) * skew(a) @ skew(a)
    assert judge("ex01_rotations", "q2", rot("z", t), u, v).passed
    assert_named(judge("ex01_rotations", "q2", raw, u, v), "unnormalised", "(u × v) / |u × v|")
    # the angle from arccos(u · v) of vectors of any length: (0.5, 0, 0) · (-0.6, 0.8, 0) = -0.3, where cos θ = -0.6
    u2, v2 = np.array([0.5, 0.0, 0.0]), np.array([-0.6, 0.8, 0.0])
    assert judge("ex01_rotations", "q2", rot("z", np.arccos(-0.6)), u2, v2).passed
    assert_named(judge("ex01_rotations", "q2", rot("z", np.arccos(-0.3)), u2, v2), "unnormalised", "arccos(u · v)")
    R_a = rot("y", 0.3)  # ex01 q3: axis e_x, angle 0.5: a student returning 2 sin(θ) k as the axis
    assert_named(
        judge("ex01_rotations", "q3", [2 * np.sin(0.5), 0, 0, 0.5], R_a, rot("x", 0.5) @ R_a), "unnormalised", "length"
    )


def test_a_row_or_a_column_with_the_wrong_sign():
    wrong = rot("x", 0.3)
    wrong[2] *= -1.0
    assert_named(judge("ex01_rotations", "q1", wrong, "x", 0.3), "sign_flip", "row 3")
    wrong = rot("z", 1.2)
    wrong[:, 0] *= -1.0
    assert_named(judge("ex01_rotations", "q1", wrong, "z", 1.2), "sign_flip", "column 1")
    T_prev = homogeneous(rot("x", 1.1), [0.0, -0.5, 0.3])
    T = T_prev @ link(0.7, 0.4, -1.0, 0.15)
    assert_named(judge("ex02_dh_frames", "q1", [0.7, 0.4, -1.0, -0.15], T_prev, T), "sign_flip", "d_i")
    assert judge("ex02_dh_frames", "q1", [0.7, 0.4, -1.0, 0.15], T_prev, T).passed


def test_an_angle_off_by_a_whole_turn():
    R_a = rot("z", 0.4)
    assert_named(
        judge("ex01_rotations", "q3", [0, 1, 0, 2.0 + 2 * np.pi], R_a, rot("y", 2.0) @ R_a), "angle_2pi", "(0, π)"
    )
    v, w, axis = [1.0, 0, 0], [0, -1.0, 0], [0, 0, 1.0]
    assert_named(judge("ex07_porter_geometric", "q3", -np.pi / 2 + 2 * np.pi, v, w, axis), "angle_2pi")


def test_the_same_rotation_outside_the_range_and_the_inverses_translation():
    R_a = rot("x", -0.8)
    assert_named(judge("ex01_rotations", "q3", [0, 0, -1, -1.0], R_a, rot("z", 1.0) @ R_a), "range", "(-k, -θ)")
    # ex01 q4: ⁰T_A inverted with -p_A, worked by hand: R_Aᵀ p_B - p_A = (3, -1, 3) - (1, 2, 3)
    T_a = homogeneous(rot("z", np.pi / 2), [1.0, 2.0, 3.0])
    T_b = homogeneous(np.eye(3), [1.0, 3.0, 3.0])
    assert judge("ex01_rotations", "q4", homogeneous(rot("z", -np.pi / 2), [1.0, 0.0, 0.0]), T_a, T_b).passed
    minus_p = homogeneous(rot("z", -np.pi / 2), [2.0, -3.0, 0.0])
    assert_named(judge("ex01_rotations", "q4", minus_p, T_a, T_b), "translation", "-R_Aᵀ p_A")
    # any other wrong translation is not "translation": the offset from {B} to {A}, and (p_B - p_A) in {0}
    verdict = judge("ex01_rotations", "q4", homogeneous(rot("z", -np.pi / 2), [-1.0, 0.0, 0.0]), T_a, T_b)
    assert not verdict.passed and verdict.mistake is None
    base = homogeneous(rot("z", -np.pi / 2), [0.0, 1.0, 0.0])
    assert_named(judge("ex01_rotations", "q4", base, T_a, T_b), "frame_coordinates", "base frame")


def test_the_turn_between_orientations_read_in_the_wrong_frame_or_the_wrong_way():
    # ex01 q3: R_a = R_x(90°), R_b = R_z(90°) R_a; R_aᵀ R_b turns about R_aᵀ e_z = e_y, R_a R_bᵀ about -e_z
    R_a = np.round(rot("x", np.pi / 2), 15)
    R_b = rot("z", np.pi / 2) @ R_a
    assert judge("ex01_rotations", "q3", [0, 0, 1, np.pi / 2], R_a, R_b).passed
    in_a = judge("ex01_rotations", "q3", [0, 1, 0, np.pi / 2], R_a, R_b)
    assert_named(in_a, "frame_coordinates", "the tool's own coordinates", "columns of R_a")
    back = judge("ex01_rotations", "q3", [0, 0, -1, np.pi / 2], R_a, R_b)
    assert_named(back, "rotation_sense", "R_b back onto R_a")
    # the question speaks of R_a and R_b only: its messages name no frame {A} or {B} it never defined
    for verdict in (in_a, back):
        assert "{A}" not in verdict.reason and "{B}" not in verdict.reason, verdict.reason


def test_the_pose_of_a_in_b_and_the_product_in_the_other_order():
    T_a = homogeneous(rot("z", np.pi / 2), [1.0, 2.0, 3.0])
    T_b = homogeneous(rot("x", 0.4), [0.5, -1.0, 2.0])
    X = right("ex01_rotations", "q4", T_a, T_b)
    assert np.allclose(T_a @ X, T_b)
    inverse = homogeneous(X[:3, :3].T, -X[:3, :3].T @ X[:3, 3])
    assert_named(judge("ex01_rotations", "q4", inverse, T_a, T_b), "inverse", "ᴮT_A")
    a_inv = homogeneous(rot("z", -np.pi / 2), -rot("z", -np.pi / 2) @ [1.0, 2.0, 3.0])
    assert_named(judge("ex01_rotations", "q4", T_b @ a_inv, T_a, T_b), "order", "other order")
    # the inverse's rotation block left untransposed (R_A applied, not undone) is not named
    wrong = homogeneous(rot("z", np.pi / 2) @ rot("x", 0.4), X[:3, 3])
    verdict = judge("ex01_rotations", "q4", wrong, T_a, T_b)
    assert not verdict.passed and verdict.mistake is None


# ------------------------------------------------------------------------------------------ DH (ex02-ex04)
def sdh(theta, d, a, alpha):
    ca, sa, ct, st = np.cos(alpha), np.sin(alpha), np.cos(theta), np.sin(theta)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])


def test_the_pan_tilt_camera_head_frame_fixed_axes_and_degrees():
    # crafted by hand: the head's frame (x forward, z up) at the camera, never turned to the camera's axes
    pan, tilt = 0.6, 0.35
    R_head = rot("z", pan) @ rot("y", tilt)
    head = homogeneous(R_head, [0.0, 0.0, 0.12] + 0.05 * R_head[:, 0])
    camera = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])  # columns: x_c, y_c, z_c in the head
    right_answer = homogeneous(R_head @ camera, head[:3, 3])
    assert judge("ex01_rotations", "q5", right_answer, pan, tilt).passed
    assert_named(judge("ex01_rotations", "q5", head, pan, tilt), "tool_frame", "head's frame")
    # the tilt about the base's fixed y0 (Ry Rz instead of Rz Ry): fixed axes where the axes move
    R_fixed = rot("y", tilt) @ rot("z", pan)
    fixed = homogeneous(R_fixed @ camera, [0.0, 0.0, 0.12] + 0.05 * R_fixed[:, 0])
    assert_named(judge("ex01_rotations", "q5", fixed, pan, tilt), "order", "moving axes")
    # the angles read as degrees
    R_deg = rot("z", np.radians(pan)) @ rot("y", np.radians(tilt))
    deg = homogeneous(R_deg @ camera, [0.0, 0.0, 0.12] + 0.05 * R_deg[:, 0])
    assert_named(judge("ex01_rotations", "q5", deg, pan, tilt), "degrees", "degrees")


def link(alpha, a, theta, d):
    """Craig's link matrix, multiplied out by hand (lecture 02 §5)."""
    ca, sa, ct, st = np.cos(alpha), np.sin(alpha), np.cos(theta), np.sin(theta)
    return np.array(
        [[ct, -st, 0.0, a], [st * ca, ct * ca, -sa, -sa * d], [st * sa, ct * sa, ca, ca * d], [0.0, 0.0, 0.0, 1.0]]
    )


def test_the_standard_dh_link_matrix_instead_of_the_modified_one():
    # q2: the four motions reversed but not undone are the standard-DH matrix of the same numbers
    params = (np.pi / 2, 0.4, -1.0, 0.15)
    assert_named(judge("ex02_dh_frames", "q2", sdh(-1.0, 0.15, 0.4, np.pi / 2), *params), "standard_dh", "standard")
    # q1: the four numbers read where a standard-DH matrix shows them (θ from column 1, α from row 3, d = p_z)
    T_prev = homogeneous(rot("y", -0.8), [0.5, 0.0, 1.0])
    L = link(0.7, 0.3, 0.5, 0.2)
    theta, alpha = np.arctan2(L[1, 0], L[0, 0]), np.arctan2(L[2, 1], L[2, 2])
    a, d = np.cos(theta) * L[0, 3] + np.sin(theta) * L[1, 3], L[2, 3]
    assert np.allclose(sdh(0.5, 0.2, 0.3, 0.7)[[0, 1, 2], 3], [0.3 * np.cos(0.5), 0.3 * np.sin(0.5), 0.2])
    verdict = judge("ex02_dh_frames", "q1", [alpha, a, theta, d], T_prev, T_prev @ L)
    assert_named(verdict, "standard_dh", "standard-DH")


def test_the_parameters_read_off_the_wrong_matrix():
    """ex02 q1 gives the world poses ⁰T_(i-1), ⁰T_i: the numbers read off ⁰T_i itself, off ⁱT_(i-1) or off
    ⁰T_i (⁰T_(i-1))⁻¹ are named, whatever d was read as (d of a matrix that is not a link matrix is ambiguous)."""
    T_prev = homogeneous(rot("x", 0.9) @ rot("z", -0.4), [0.3, -0.2, 0.7])
    L = link(-np.pi / 2, 0.25, 0.5, -0.3)
    T = T_prev @ L

    def lecture_reading(M):
        alpha = np.arctan2(-M[1, 2], M[2, 2])
        return [alpha, M[0, 3], np.arctan2(-M[0, 1], M[0, 0]), -np.sin(alpha) * M[1, 3] + np.cos(alpha) * M[2, 3]]

    assert judge("ex02_dh_frames", "q1", lecture_reading(np.linalg.inv(T_prev) @ T), T_prev, T).passed
    for M, key, word in (
        (T, "base_frame", "⁰T_i"),
        (np.linalg.inv(T) @ T_prev, "inverse", "other way round"),
        (T @ np.linalg.inv(T_prev), "order", "(⁰T_{i-1})⁻¹"),
    ):
        got = lecture_reading(M)
        assert_named(judge("ex02_dh_frames", "q1", got, T_prev, T), key, word)
        got[3] = M[2, 3]  # d read off another entry: the same mistake
        assert_named(judge("ex02_dh_frames", "q1", got, T_prev, T), key, word)


def test_the_inverse_link_matrix_s_mistakes():
    """ex02 q2 asks for ⁱT_(i-1): each way of getting the four motions' undoing wrong is named as what it is."""
    params = (0.7, 0.4, -1.2, 0.3)
    al, a, th, d = params
    F = link(*params)
    R, p = F[:3, :3], F[:3, 3]
    inv = homogeneous(R.T, -R.T @ p)
    assert judge("ex02_dh_frames", "q2", inv, *params).passed
    assert_named(judge("ex02_dh_frames", "q2", F, *params), "inverse", "ⁱ⁻¹T_i itself")
    assert_named(judge("ex02_dh_frames", "q2", link(-al, -a, -th, -d), *params), "order", "last step")
    assert_named(judge("ex02_dh_frames", "q2", inv.T, *params), "transposed", "inverse transposed")
    assert_named(judge("ex02_dh_frames", "q2", F.T, *params), "transposed", "link matrix transposed")
    assert_named(judge("ex02_dh_frames", "q2", homogeneous(R.T, -p), *params), "translation", "-p")
    assert_named(judge("ex02_dh_frames", "q2", homogeneous(R.T, p), *params), "translation", "is p")
    # a translation that is neither -p nor p: what differs is said, no mistake named
    verdict = judge("ex02_dh_frames", "q2", homogeneous(R.T, -R @ p), *params)
    assert not verdict.passed and verdict.mistake is None, verdict


def test_link_matrices_multiplied_in_the_wrong_order():
    table = np.array([[0.0, 0, 0.3, 0.5, 0], [-np.pi / 2, 0.2, 0, 0.1, 1], [np.pi / 2, 0, -0.4, 0, 0]])
    q = np.array([0.4, 0.25, -1.0])
    links = []
    for (alpha, a, theta, d, sigma), qi in zip(table, q, strict=True):
        links.append(link(alpha, a, theta + (0 if sigma else qi), d + (qi if sigma else 0)))
    assert judge("ex03_puma_fk", "q1", links[0] @ links[1] @ links[2], table, q, 0).passed
    assert_named(judge("ex03_puma_fk", "q1", links[2] @ links[1] @ links[0], table, q, 0), "order", "reverse")
    # in frame {1}: the last two link matrices only; the whole product is the base frame's pose, named so
    assert judge("ex03_puma_fk", "q1", links[1] @ links[2], table, q, 1).passed
    assert_named(judge("ex03_puma_fk", "q1", links[2] @ links[1], table, q, 1), "order", "reverse")
    assert_named(judge("ex03_puma_fk", "q1", links[0] @ links[1] @ links[2], table, q, 1), "base_frame", "{k}")


def test_the_printed_misprint_used_as_printed():
    q, L = np.array([0.3, 0.8, -0.5, 0.2, 1.0]), (360.0, 135.0, 250.0, 215.0, 100.0, np.eye(4))  # no tool: E = I
    T = right("ex04_mk3_fk", "q2", q, *L)
    # the printed 4T5: its offset (0, 0, -d5) instead of (0, -d5, 0); from {4}, (0, -d5, 0) is d5 z5
    wrong = T.copy()
    wrong[:3, 3] = (
        T[:3, 3]
        - 100.0 * T[:3, 2]
        + T[:3, :3] @ (right("ex02_dh_frames", "q2", np.pi / 2, 0, 1.0, 0)[:3, :3] @ [0, 0, -100.0])
    )
    assert_named(judge("ex04_mk3_fk", "q2", wrong, q, *L), "printed_formula", "misprinted")


def test_an_offset_along_the_wrong_axis_or_with_the_wrong_sign():
    T = homogeneous(rot("y", 0.4) @ rot("z", 1.0), [600.0, 50.0, 260.0])
    torch = homogeneous(rot("y", 0.5), [20.0, 0.0, 150.0])  # ex04 q1: the flange T holds a torch, the task gives T E
    args = (T @ torch, 100.0, torch)
    assert judge("ex04_mk3_fk", "q1", T[:3, 3] - 100 * T[:3, 2], *args).passed
    assert_named(judge("ex04_mk3_fk", "q1", T[:3, 3] - 100 * T[:3, 0], *args), "wrong_axis", "x5")
    assert_named(judge("ex04_mk3_fk", "q1", T[:3, 3] + 100 * T[:3, 2], *args), "offset_sign", "beyond")
    Tt = T @ torch  # lecture 04's w = p - d5 z5 applied to the tool's pose
    assert_named(judge("ex04_mk3_fk", "q1", Tt[:3, 3] - 100 * Tt[:3, 2], *args), "lecture_mechanism", "E⁻¹")
    E = homogeneous(rot("x", 0.3), [0.1, 0.0, 0.05])  # ex06 q1: the hand holds a tool E, the task gives T E
    TE = T @ E
    assert judge("ex06_porter_explicit", "q1", T[:3, 3] - 0.3 * T[:3, 0], TE, 0.3, E).passed
    assert_named(judge("ex06_porter_explicit", "q1", T[:3, 3] - 0.3 * T[:3, 2], TE, 0.3, E), "wrong_axis", "z5")
    assert_named(judge("ex06_porter_explicit", "q1", TE[:3, 3] - 0.3 * TE[:3, 0], TE, 0.3, E), "tool_frame", "T_tool")
    TEE = TE @ E
    assert_named(judge("ex06_porter_explicit", "q1", TEE[:3, 3] - 0.3 * TEE[:3, 0], TE, 0.3, E), "order", "side")


# ------------------------------------------------------------------------------------------ Porter (ex05-ex07)
def porter_factors(q, l1, l3, l4, printed=False, hand="y", through="p5"):
    """The nine motions of Porter's chain whose sixth joint turns about ``hand`` (ex05 q1: y4 through p5)."""
    a1, a2, q2, a3, a4, a5 = q

    def R(axis, t):
        return homogeneous(rot(axis, t), np.zeros(3))

    def tr(axis, d):
        return homogeneous(np.eye(3), {"x": [d, 0, 0], "z": [0, 0, d]}[axis])

    slide = [] if printed else [tr("x", q2)]
    wrist = [tr("x", l4), R(hand, a5)] if through == "p5" else [R(hand, a5), tr("x", l4)]
    return [R("z", a1), tr("z", l1), R("y", a2), *slide, R("y", a3), tr("z", -l3), R("z", a4), *wrist]


def test_porters_product_printed_without_the_slide_and_in_the_reverse_order():
    q, L = np.array([0.3, 0.7, 1.3, -0.4, 0.9, 0.6]), (1.0, 0.5, 0.3)
    F = porter_factors(q, *L)
    assert judge("ex05_porter_fk", "q1", np.linalg.multi_dot(F), q, *L).passed
    assert_named(judge("ex05_porter_fk", "q1", np.linalg.multi_dot(F[::-1]), q, *L), "order", "moving")
    printed = np.linalg.multi_dot(porter_factors(q, *L, printed=True))
    assert_named(judge("ex05_porter_fk", "q1", printed, q, *L), "printed_formula", "as printed")
    assert_named(judge("ex05_porter_fk", "q1", np.linalg.inv(np.linalg.multi_dot(F)), q, *L), "inverse")


def test_the_pitching_hand_is_not_lecture_05s_hand_and_turns_about_p5():
    q, L = np.array([0.3, 0.7, 1.3, -0.4, 0.9, 0.6]), (1.0, 0.5, 0.3)
    lecture = np.linalg.multi_dot(porter_factors(q, *L, hand="x"))  # lecture 05's product, copied
    assert_named(judge("ex05_porter_fk", "q1", lecture, q, *L), "lecture_mechanism", "y4 through p5")
    about_p4 = np.linalg.multi_dot(porter_factors(q, *L, through="p4"))
    assert_named(judge("ex05_porter_fk", "q1", about_p4, q, *L), "joint_line", "through p4")


def test_the_printed_normal_and_the_printed_rod_length():
    name = "ex07_porter_geometric"
    T, L = EXERCISES[name].question("q1").public[0][0], (1.0, 0.5, 0.3)
    n = right(name, "q1", T, 1.0, 0.3)
    assert_named(judge(name, "q1", -n, T, 1.0, 0.3), "printed_formula", "-y1")
    assert_named(judge(name, "q1", 3 * n, T, 1.0, 0.3), "unnormalised")
    p4, x5 = T[:3, 3] - 0.3 * T[:3, 0], T[:3, 0]
    z4 = np.cross(T[:3, :3] @ n, x5) / np.linalg.norm(np.cross(T[:3, :3] @ n, x5))  # n is in F5's coordinates

    def in_hand(points):  # the question asks for the points in the hand frame F5
        return (np.asarray(points) - T[:3, 3]) @ T[:3, :3]

    assert judge(name, "q2", in_hand([p4 - 0.5 * z4, p4 + 0.5 * z4]), T, *L).passed  # any order
    assert_named(judge(name, "q2", in_hand([p4 + 0.3 * z4, p4 - 0.3 * z4]), T, *L), "printed_formula", "l4")
    assert_named(judge(name, "q2", in_hand([p4 + 0.5 * z4, p4 + 0.5 * z4]), T, *L), "duplicates")
    assert_named(judge(name, "q2", [p4 - 0.5 * z4, p4 + 0.5 * z4], T, *L), "frame_coordinates", "hand frame")
    assert_named(judge(name, "q1", T[:3, :3] @ n, T, 1.0, 0.3), "frame_coordinates", "R05ᵀ")


def test_the_unsigned_angle():
    v, w, axis = np.array([1.0, 0, 0]), np.array([-1.0, -1.0, 0]), np.array([0, 0, 1.0])
    assert judge("ex07_porter_geometric", "q3", -3 * np.pi / 4, v, w, axis).passed
    assert_named(judge("ex07_porter_geometric", "q3", 3 * np.pi / 4, v, w, axis), "unsigned_angle", "unsigned")


def test_ik_sets_any_order_but_no_duplicate_no_missing_branch_no_negative_stroke():
    name = "ex06_porter_explicit"
    T, *L = EXERCISES[name].question("q2").public[1]  # (T, l1, l2, l3, l4): a short fixed part, four rows
    S = right(name, "q2", T, *L)
    assert len(S) == 4
    assert (
        judge(name, "q2", S[::-1], T, *L).passed
        and judge(name, "q2", S[[2, 0, 3, 1]] + 2 * np.pi * np.array([1, 0, 0, 0, -1, 0]), T, *L).passed
    )
    assert_named(judge(name, "q2", np.vstack([S, S[:1]]), T, *L), "duplicates", "same configuration")
    missing = judge(name, "q2", S[:2], T, *L)
    assert_named(missing, "missing_solutions", "misses 2 of the 4")
    assert "back/" in missing.reason or "front/" in missing.reason  # the branches are named
    a1, a2, q2, a3, a4, a5 = S[0]
    other = np.array([a1, a2 + np.pi, -q2 - 2 * L[1], a3 - np.pi, a4, a5])  # the rod's length negated: q2 < 0
    assert_named(judge(name, "q2", np.vstack([S[1:], other]), T, *L), "negative_stroke", "q2 =")
    in_degrees = S.copy()
    in_degrees[:, [0, 1, 3, 4, 5]] = np.degrees(S[:, [0, 1, 3, 4, 5]])
    assert_named(judge(name, "q2", in_degrees, T, *L), "degrees")
    bad = S.copy()
    bad[1, 3] += 0.2
    assert_named(judge(name, "q2", bad, T, *L), "not_a_solution", "row 2")


def test_the_telescopic_rod_keeps_only_the_rows_it_can_take():
    name = "ex06_porter_explicit"
    T, l1, l2, l3, l4 = EXERCISES[name].question("q2").public[0]  # l2 between the two rod lengths: two rows
    S = right(name, "q2", T, l1, l2, l3, l4)
    assert len(S) == 2 and judge(name, "q2", S, T, l1, l2, l3, l4).passed
    rows = right(name, "q2", T, l1, 0.0, l3, l4)  # Porter's four, the rod's whole length as the stroke
    kept = rows - [0, 0, l2, 0, 0, 0]  # the fixed part subtracted, but every row kept
    assert_named(judge(name, "q2", kept, T, l1, l2, l3, l4), "negative_stroke", "shorter than its fixed part")
    assert_named(judge(name, "q2", rows, T, l1, l2, l3, l4), "not_a_solution")  # lecture 06 copied: no l2


def test_a_stroke_limit_drops_rows_and_may_leave_none():
    name = "ex06_porter_explicit"
    q = EXERCISES[name].question("q4")
    (T, *L, within), (_, *_, short) = q.public
    S = right(name, "q4", T, *L, within)
    assert len(S) == 2 and judge(name, "q4", S, T, *L, within).passed
    assert judge(name, "q4", np.empty((0, 6)), T, *L, short).passed and judge(name, "q4", [], T, *L, short).passed
    every = right(name, "q2", T, L[0], 0.0, *L[1:])
    assert_named(judge(name, "q4", every, T, *L, within), "stroke_limit", "beyond the stroke limit")
    assert_named(judge(name, "q4", every, T, *L, short), "stroke_limit", "out of reach")


def test_a_tool_composed_on_the_wrong_side():
    name, L = "ex06_porter_explicit", (1.0, 0.5, 0.3)
    T_tool, *_, E = EXERCISES[name].question("q3").public[0]
    assert judge(name, "q3", right(name, "q3", T_tool, *L, E), T_tool, *L, E).passed
    wrong = right(name, "q2", T_tool @ E, L[0], 0.0, *L[1:])  # F05 = T_tool E instead of T_tool E^-1
    assert_named(judge(name, "q3", wrong, T_tool, *L, E), "order", "wrong side")
    assert_named(judge(name, "q3", right(name, "q2", T_tool, L[0], 0.0, *L[1:]), T_tool, *L, E), "tool_frame", "F5")


def test_the_parallel_planes_representative():
    name, L = "ex07_porter_geometric", (1.0, 0.5, 0.3)
    T = EXERCISES[name].question("q4").public[0][0]
    good = right(name, "q4", T, *L)
    assert judge(name, "q4", good, T, *L).passed
    back = [q for q in right("ex06_porter_explicit", "q2", T, L[0], 0.0, *L[1:]) if np.cos(q[0] - good[0]) < 0]
    assert_named(judge(name, "q4", back[0], T, *L), "back_plane", "from the back")
    # the same construction with the elbow on the far side of the circle: a longer stroke
    x5, z5 = T[:3, 0], T[:3, 2]
    p2, p4 = np.array([0, 0, 1.0]), T[:3, 3] - 0.3 * x5
    n = T[:3, :3] @ right(name, "q1", T, 1.0, 0.3)  # q1 answers in the hand frame F5
    p3 = p4 - 0.5 * (p2 - p4) / np.linalg.norm(p2 - p4)

    def ang(v, w, a):
        return np.arctan2(a @ np.cross(v, w), v @ w)

    far = [
        np.arctan2(p4[1], p4[0]),
        ang(p2, p3 - p2, n) - np.pi / 2,
        np.linalg.norm(p3 - p2),
        ang(p3 - p2, p4 - p3, n) - np.pi / 2,
        ang(n, x5, (p3 - p4) / 0.5) + np.pi / 2,
        ang(p3 - p4, z5, x5),
    ]
    assert_named(judge(name, "q4", far, T, *L), "not_minimal", "smallest stroke")


# ------------------------------------------------------------------------------------------ DH tables
def rrp(h, d2):
    H = np.pi / 2
    return np.array([[0.0, 0.0, 0.0, h, 0], [H, 0.0, H, -d2, 0], [H, 0.0, 0.0, 0.0, 1]])


@pytest.mark.parametrize(
    ("change", "key", "words"),
    [
        (lambda t: t[:, [0, 1, 2, 3, 4]] * [180 / np.pi, 1, 180 / np.pi, 1, 1], "degrees", ("degrees",)),
        (lambda t: np.c_[np.r_[t[1:, 0], 0.0], t[:, 1], t[:, 2:]], "standard_dh", ("standard-DH", "Craig")),
        (lambda t: t * [1, 1, 1, 1, 0], "joint_type", ("joint 3 is prismatic",)),
        (lambda t: t - [[0, 0, 0, 0.8, 0], [0, 0, 0, 0, 0], [0, 0, 0, 0, 0]], "base_frame", ("frame {0}",)),
        (lambda t: t + [[0, 0, 0, 0, 0], [0, 0, 0, 0, 0], [0, 0, np.pi / 2, 0, 0]], "tool_frame", ("tool frame",)),
    ],
    ids=["degrees", "standard-dh", "joint-type", "base-frame", "tool-frame"],
)
def test_a_wrong_table_is_named(change, key, words):
    verdict = judge("ex02_dh_frames", "q3", change(rrp(0.8, 0.2)), 0.8, 0.2)
    assert_named(verdict, key, *words)


def test_a_table_right_only_at_q_zero_and_a_joint_turning_the_wrong_way():
    H, h, d2 = np.pi / 2, 0.8, 0.2
    # joint 1's axis displaced along x0, the displacement undone by a1: right at q = 0 only
    shifted = np.array([[0.0, 0.3, 0.0, h, 0], [H, -0.3, H, -d2, 0], [H, 0.0, 0.0, 0.0, 1]])
    assert_named(judge("ex02_dh_frames", "q3", shifted, h, d2), "only_at_zero", "q = 0", "joint 1")
    # z2 along +y0: positive q2 lowers the tip; the offsets keep q = 0 right
    flipped = np.array([[0.0, 0.0, 0.0, h, 0], [-H, 0.0, -H, d2, 0], [-H, 0.0, 0.0, 0.0, 1]])
    assert_named(judge("ex02_dh_frames", "q3", flipped, h, d2), "joint_sign", "joint 2")


# ------------------------------------------------------------------------------------------ the three-step arm (ex08)
def test_the_straight_start_the_other_elbow_and_the_wrong_side():
    name = "ex08_three_step"
    w, F, l1, l2, elbow, tb, Fb = EXERCISES[name].question("q4").public[0]
    t0 = np.arctan2(w[1], w[0]) - np.pi / 2  # exercise 8's arm reads its base angle from e_y
    K = rot("z", t0 - tb[0])
    assert judge(name, "q1", K @ Fb, w, tb, Fb).passed
    assert_named(judge(name, "q1", rot("z", t0) @ Fb, w, tb, Fb), "straight_start", "straight arm")
    assert_named(judge(name, "q1", rot("z", t0 + np.pi / 2 - tb[0]) @ Fb, w, tb, Fb), "lecture_mechanism", "e_y")
    assert_named(judge(name, "q1", K, w, tb, Fb), "straight_start")
    assert_named(judge(name, "q1", Fb @ K, w, tb, Fb), "order", "right")
    other = right(name, "q2", w, l1, l2, "down")
    assert_named(judge(name, "q2", other, w, l1, l2, "up"), "branch", "other elbow")
    t1, t2 = right(name, "q2", w, l1, l2, "up")
    assert_named(judge(name, "q2", [t1, t2 - t1], w, l1, l2, "up"), "lecture_mechanism", "upper arm")
    g0, (t1, t2) = np.arctan2(w[1], w[0]), right(name, "q2", w, l1, l2, elbow)
    a = np.array([np.sin(g0), -np.cos(g0), 0.0])  # the arm plane's axis (its direction g0 from e_x)
    # lecture 08 copied: the base from e_x, the forearm turned by (θ1 + θ2) - (θ̄1 + θ̄2) with θ2 from the upper arm
    lecture = rot_about(a, t2 - (tb[1] + tb[2])) @ rot("z", g0 - tb[0]) @ Fb
    assert_named(judge(name, "q3", lecture, w, l1, l2, elbow, tb, Fb), "lecture_mechanism", "parallelogram")
    assert judge(name, "q3", rot_about(a, t2 - tb[2]) @ K @ Fb, w, l1, l2, elbow, tb, Fb).passed
    F2 = right(name, "q3", w, l1, l2, elbow, tb, Fb)
    assert judge(name, "q4", F @ F2.T, w, F, l1, l2, elbow, tb, Fb).passed
    assert_named(judge(name, "q4", F2.T @ F, w, F, l1, l2, elbow, tb, Fb), "order", "moving")
    assert_named(judge(name, "q4", F2 @ F.T, w, F, l1, l2, elbow, tb, Fb), "transposed")


def zyz(R):
    return [
        np.arctan2(R[1, 2], R[0, 2]),
        np.arctan2(np.hypot(R[0, 2], R[1, 2]), R[2, 2]),
        np.arctan2(R[2, 1], -R[2, 0]),
    ]


def test_wrist_angles_about_the_fixed_axes():
    name = "ex08_three_step"
    args = EXERCISES[name].question("q5").public[0]
    w, F, l1, l2, elbow, tb, Fb = args
    F2 = right(name, "q3", w, l1, l2, elbow, tb, Fb)
    assert judge(name, "q5", zyz(F2.T @ F), *args).passed
    a, b, c = zyz(F2.T @ F)  # an equivalent triple: (φ + π, -ϑ, ψ + π)
    assert judge(name, "q5", [a + np.pi, -b, c + np.pi], *args).passed
    assert_named(judge(name, "q5", zyz(F @ F2.T), *args), "order", "fixed axes")
    assert_named(judge(name, "q5", np.degrees(zyz(F2.T @ F)), *args), "degrees")


# ---------------------------------------------------------------------------------- PUMA-560 IK, paths (ex09, ex10)
def test_the_nearest_solution_and_unwrapped_distances():
    # ex09 q3 (the PUMA's nearest solution) was dropped (issue 22): its case and reference judged directly
    import puma_course_bank._reference.motion as motion
    from puma_course.grading.judge.judges import nearest_judge

    L = (0.4318, 0.0203, 0.15005, 0.4318)
    T = motion.puma_fk(np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0]), *L)
    q_ref = np.array([3.1, 1.0, 2.9, -3.1, 2.4, 0.9])
    expected, nearest_of = motion.puma_nearest_expected(T, q_ref, *L), nearest_judge()
    S = np.asarray(expected["solutions"])
    d = np.angle(np.exp(1j * (S - q_ref)))
    plain = S - q_ref
    nearest, unwrapped = S[np.argmin(np.sum(d * d, 1))], S[np.argmin(np.sum(plain * plain, 1))]
    assert not np.allclose(nearest, unwrapped)  # the case is built so that wrapping decides
    assert nearest_of(nearest, expected, (T, q_ref, *L)).passed
    assert_named(nearest_of(unwrapped, expected, (T, q_ref, *L)), "unwrapped_distance", "wrapped")
    farther = next(S[i] for i in np.argsort(np.sum(d * d, 1))[1:] if not np.allclose(S[i], unwrapped))
    told = nearest_of(farther, expected, (T, q_ref, *L))
    assert_named(told, "not_nearest", "not the nearest")
    assert "not wrapped" not in (told.reason or "")  # never the heuristic "nearest if not wrapped" (issue 22)
    q, r, w = EXERCISES["ex10_trajectories"].question("q1").public[0]
    assert_named(judge("ex10_trajectories", "q1", np.sqrt(np.sum(w * (q - r) ** 2)), q, r, w), "unwrapped_distance")
    d = np.angle(np.exp(1j * (q - r)))  # lecture 10's D, the weights left out (worked out here, not by the bank)
    assert judge("ex10_trajectories", "q1", np.sqrt(np.sum(w * d * d)), q, r, w).passed
    assert_named(judge("ex10_trajectories", "q1", np.sqrt(np.sum(d * d)), q, r, w), "lecture_mechanism", "weight")


def test_solutions_sorted_in_another_order():
    name = "ex10_trajectories"
    S, q_prev, w = EXERCISES[name].question("q2").public[0]
    good = right(name, "q2", S, q_prev, w)
    d = np.angle(np.exp(1j * (S - q_prev)))
    assert np.allclose(good, S[np.argsort(np.sum(w * d * d, axis=1), kind="stable")])  # by hand: weighted, wrapped
    assert judge(name, "q2", good, S, q_prev, w).passed
    assert_named(judge(name, "q2", good[::-1], S, q_prev, w), "solution_order", "another order")
    assert_named(judge(name, "q2", np.vstack([good, good[:1]]), S, q_prev, w), "duplicates")
    unweighted = S[np.argsort(np.sum(d * d, axis=1), kind="stable")]
    assert_named(judge(name, "q2", unweighted, S, q_prev, w), "lecture_mechanism", "unweighted")


def test_a_robot_in_a_cell_solved_as_if_at_the_origin_or_without_its_tool():
    name = "ex09_puma_ik"
    T_world, B, d6 = EXERCISES[name].question("q5").public[0]
    L = (0.4318, 0.0203, 0.15005, 0.4318)
    tool = homogeneous(np.eye(3), [0, 0, d6])
    assert judge(
        name, "q5", right(name, "q2", np.linalg.inv(B) @ T_world @ np.linalg.inv(tool), *L), T_world, B, d6
    ).passed
    assert_named(
        judge(name, "q5", right(name, "q2", T_world @ np.linalg.inv(tool), *L), T_world, B, d6),
        "base_frame",
        "world origin",
    )
    assert_named(judge(name, "q5", right(name, "q2", np.linalg.inv(B) @ T_world, *L), T_world, B, d6), "tool_frame")
    assert_named(
        judge(name, "q5", right(name, "q2", np.linalg.inv(B) @ T_world @ tool, *L), T_world, B, d6), "offset_sign"
    )


def test_a_path_that_jumps_or_starts_elsewhere():
    name = "ex10_trajectories"
    path, q0, d = EXERCISES[name].question("q3").public[0]
    good = right(name, "q3", path, q0, d)
    assert judge(name, "q3", good, path, q0, d).passed
    # the naive rule: at every pose the solution of the same label as the start, flip or not by the sign of θ5
    expected = EXERCISES[name].question("q3").reference(path, q0, d)
    jumpy = good.copy()
    k = len(good) // 2
    jumpy[k:, 3] += np.pi
    jumpy[k:, 4] *= -1
    jumpy[k:, 5] += np.pi  # the other wrist solution from the middle on: same poses, a jump of about 255°
    assert_named(EXERCISES[name].question("q3").judge(jumpy, expected, (path, q0, d)), "jump", "joint(s) 4, 5, 6")
    other = good.copy()
    other[:, 3] += np.pi
    other[:, 4] *= -1
    other[:, 5] += np.pi  # the whole path on the other wrist branch: smooth, but not where the arm stands
    assert_named(EXERCISES[name].question("q3").judge(other, expected, (path, q0, d)), "start_jump", "q0")
    wrist = right(
        "ex09_puma_ik",
        "q2",
        path[0] @ np.linalg.inv(homogeneous(np.eye(3), [0, 0, d])),
        0.4318,
        0.0203,
        0.15005,
        0.4318,
    )
    assert len(wrist) == 8


# ------------------------------------------------------------------------------------------ the machinery
def test_every_emitted_key_has_a_title_and_a_mistake_with_an_unknown_key_is_refused():
    for ex in EXERCISES.values():
        for q in ex.questions:
            assert all(base_key(m.key) in TITLES for m in q.mistakes)  # "rotation_sense#sign": a variant
    with pytest.raises(ValueError, match="key: expected one of"):
        Mistake("typo", lambda *a: None)


def test_no_diagnosis_without_a_matching_mistake_and_broken_checks_are_skipped():
    R = rot("z", 0.7)
    verdict = judge("ex01_rotations", "q1", R + 0.05, "z", 0.7)
    assert not verdict.passed and verdict.mistake is None and verdict.reason.startswith("values differ")

    def broken(got, expected, args, reference):
        raise ZeroDivisionError

    assert diagnose((Mistake("order", broken), matches("order", "reversed", lambda: R.T)), R.T, R, (), None) == (
        "order",
        "reversed",
    )
    assert diagnose((matches("order", "x", lambda: R.T),), "text", R, (), None) is None
    assert close([1.0, np.nan], np.array([1.0, 1.0])) is False


def test_a_mistake_that_gives_the_right_answer_is_not_reported():
    # about an axis whose rotation equals its transpose (a half turn) a "transposed" diagnosis would be wrong
    R = rot("z", np.pi)
    assert judge("ex01_rotations", "q1", R, "z", np.pi).passed
    assert judge("ex01_rotations", "q1", R + 0.5, "z", np.pi).mistake is None


def test_every_mistake_the_graders_name_has_a_crafted_case_in_this_file():
    from pathlib import Path

    source = Path(__file__).read_text(encoding="utf-8")
    untested = [key for key in TITLES if f'"{key}"' not in source]
    assert not untested, untested


def test_the_quintic_time_scaling_and_the_short_way_round():
    name = "ex10_trajectories"
    q0, q1, T, t = EXERCISES[name].question("q4").public[1]
    dq, tau = np.angle(np.exp(1j * (q1 - q0))), t / T
    quintic = q0 + (10 * tau**3 - 15 * tau**4 + 6 * tau**5)[:, None] * dq  # worked from lecture 10 §5
    assert judge(name, "q4", quintic, q0, q1, T, t).passed
    assert judge(name, "q4", np.angle(np.exp(1j * quintic)), q0, q1, T, t).passed  # angles a whole turn away
    assert_named(judge(name, "q4", q0 + tau[:, None] * dq, q0, q1, T, t), "time_scaling", "constant speed")
    assert_named(judge(name, "q4", q0 + (3 * tau**2 - 2 * tau**3)[:, None] * dq, q0, q1, T, t), "time_scaling", "cubic")
    unwrapped = q0 + (10 * tau**3 - 15 * tau**4 + 6 * tau**5)[:, None] * (q1 - q0)
    assert_named(judge(name, "q4", unwrapped, q0, q1, T, t), "unwrapped_distance", "wrap")


def test_the_nearest_attainable_pose_on_the_rail_and_its_mistakes():
    # worked by hand: the carriage at s = 200 mm, the tool point 300 mm ahead of the base axis (y = 200 too), so the
    # arm plane is y = 200 with normal m = e_y; the goal's approach z = Rz(30°) Ry(120°) e_z = (0.75, 0.433, -0.5)
    # leaves it by asin(0.433) = 25.66°, and Rodrigues turns the frame about z × z' onto z' = (0.832, 0, -0.555)
    name, s = "ex04_mk3_fk", 200.0
    R = rot("z", np.radians(30.0)) @ rot("y", np.radians(120.0))
    T = homogeneous(R, [300.0, 200.0, 250.0])
    z = R[:, 2]
    zn = np.array([z[0], 0.0, z[2]]) / np.hypot(z[0], z[2])
    assert np.allclose(zn, [0.83205, 0.0, -0.5547], atol=1e-5)
    k = np.cross(z, zn) / np.linalg.norm(np.cross(z, zn))
    th = np.arcsin(z[1])
    assert abs(np.degrees(th) - 25.66) < 0.01

    def turned(angle):
        K = skew(k)
        return homogeneous((np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K) @ R, T[:3, 3])

    assert judge(name, "q4", turned(th), T, s).passed
    assert judge(name, "q4", T, T, s).passed is False  # the goal itself is not attainable
    assert_named(judge(name, "q4", turned(-th), T, s), "rotation_sense", "wrong way")
    only_z = T.copy()
    only_z[:3, 2] = zn
    assert_named(judge(name, "q4", only_z, T, s), "projected_only", "whole frame")
    keep_x = T.copy()
    x = R[:, 0] - (R[:, 0] @ zn) * zn
    keep_x[:3, 0], keep_x[:3, 1], keep_x[:3, 2] = x / np.linalg.norm(x), np.cross(zn, x / np.linalg.norm(x)), zn
    assert_named(judge(name, "q4", keep_x, T, s), "not_smallest_turn", "x5 was kept")
    # the plane through the rail frame's z0 axis: the normal (-200, 300, 0) / |.| instead of e_y
    m0 = np.array([-200.0, 300.0, 0.0]) / np.hypot(200.0, 300.0)
    z0 = (z - (m0 @ z) * m0) / np.linalg.norm(z - (m0 @ z) * m0)
    k0 = np.cross(z, z0) / np.linalg.norm(np.cross(z, z0))
    K0, t0 = skew(k0), np.arcsin(abs(m0 @ z))
    rail_origin = homogeneous((np.eye(3) + np.sin(t0) * K0 + (1 - np.cos(t0)) * K0 @ K0) @ R, T[:3, 3])
    assert_named(judge(name, "q4", rail_origin, T, s), "base_frame", "carriage")
    # an attainable goal (its approach in the plane y = 200) comes back unchanged
    Ta = homogeneous(rot("y", np.radians(120.0)), [300.0, 200.0, 250.0])
    assert judge(name, "q4", Ta, Ta, s).passed


# ------------------------------------------------------------------------------ issue 22: the new questions
def test_xyz_angles_at_the_gimbal_lock_and_in_the_lecture_s_roll_pitch_yaw():
    name = "ex01_rotations"
    (Rs,) = EXERCISES[name].question("q6").public[0]  # a general rotation, Rx(0.7) Ry(π/2), another general one
    good = np.asarray(right(name, "q6", Rs))
    assert np.allclose(good[1], [0.7, np.pi / 2, 0.0])  # by hand: at the lock c = 0, a = 0.7
    assert judge(name, "q6", good, Rs).passed
    naive = good.copy()
    naive[1] = [np.arctan2(-Rs[1][1, 2], Rs[1][2, 2]), np.pi / 2, np.arctan2(-Rs[1][0, 1], Rs[1][0, 0])]
    assert_named(judge(name, "q6", naive, Rs), "gimbal_lock", "atan2(0, 0)")
    split = good.copy()
    split[1] = [0.2, np.pi / 2, 0.5]  # the same rotation (a + c = 0.7), not the representative asked for
    verdict = judge(name, "q6", split, Rs)
    assert not verdict.passed and verdict.mistake is None
    rpy = np.array([[np.arctan2(R[2, 1], R[2, 2]), np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0])),
                     np.arctan2(R[1, 0], R[0, 0])] for R in Rs])  # fmt: skip
    assert_named(judge(name, "q6", rpy, Rs), "order", "roll, pitch, yaw")


def test_det_j_and_the_lost_direction_in_the_controller_s_joint_values():
    name, L = "ex09_puma_ik", (0.4318, 0.0203, 0.15005, 0.4318)
    zero = np.array([0.0, -np.pi / 2, -np.pi / 2, 0.0, 0.0, 0.0])
    q = np.array([0.3, 0.2, -0.4, 0.1, 0.9, 0.5])
    t = q + zero  # the lecture's values: det J = -a2 (a3 s3 + d4 c3) X s5 (lecture 09 §9)
    X = L[0] * np.cos(t[1]) + L[1] * np.cos(t[1] + t[2]) - L[3] * np.sin(t[1] + t[2])
    det = -L[0] * (L[1] * np.sin(t[2]) + L[3] * np.cos(t[2])) * X * np.sin(t[4])
    assert judge(name, "q3", det, q, *L).passed
    assert_named(judge(name, "q3", -det, q, *L), "sign_flip", "wrong sign")
    X0 = L[0] * np.cos(q[1]) + L[1] * np.cos(q[1] + q[2]) - L[3] * np.sin(q[1] + q[2])
    lecture = -L[0] * (L[1] * np.sin(q[2]) + L[3] * np.cos(q[2])) * X0 * np.sin(q[4])
    assert_named(judge(name, "q3", lecture, q, *L), "joint_zero", "straight up")
    # stretched: the wrist centre cannot move away from the base origin, u = p / |p|
    q_elbow = np.array([0.5, -0.3, np.arctan2(-L[3], L[1]), 0.2, 1.0, 0.1]) - zero
    from puma_course.kinematics.puma560 import Puma560

    p = Puma560(*L).fk(q_elbow + zero)[:3, 3]
    assert judge(name, "q4", p / np.linalg.norm(p), q_elbow, *L).passed
    assert_named(judge(name, "q4", -p / np.linalg.norm(p), q_elbow, *L), "sign_flip", "u · p > 0")


def test_a_standard_table_rewritten_and_left_as_it_was():
    name = "ex02_dh_frames"
    (std,) = EXERCISES[name].question("q4").public[0]
    good = np.array(std, dtype=float)
    good[1:, :2], good[0, :2] = std[:-1, :2], 0.0  # α and a move down one row
    assert judge(name, "q4", good, std).passed
    assert_named(judge(name, "q4", np.array(std, dtype=float), std), "standard_dh", "standard-DH")


# ------------------------------------------------------------------------------------------ the student-eye review
def test_xyz_angles_in_degrees_are_named_on_every_row():
    """ex01 q6 returns a (k, 3) array of angles: degrees are recognised in every row, not the first only."""
    q = EXERCISES["ex01_rotations"].question("q6")
    for args in q.public:
        assert_named(judge("ex01_rotations", "q6", np.degrees(right("ex01_rotations", "q6", *args)), *args), "degrees")


def test_the_lost_direction_with_the_lectures_joint_values_or_not_of_length_one():
    """ex09 q4: the solution's method without the controller's zero (the arm then not singular), and a direction
    of length 2, on every public case."""
    from puma_course.kinematics import Puma560

    q = EXERCISES["ex09_puma_ik"].question("q4")

    def lecture_values(qc, a2, a3, d3, d4):  # the solution's method, θ taken as the lecture's
        t = np.asarray(qc, dtype=float)
        p = Puma560(a2, a3, d3, d4).fk(t)[:3, 3]
        if abs(a3 * np.sin(t[2]) + d4 * np.cos(t[2])) < 1e-9:
            return p / np.linalg.norm(p)
        u = np.array([p[0], p[1], 0.0])
        return u / np.linalg.norm(u)

    for args in q.public:
        assert_named(judge("ex09_puma_ik", "q4", lecture_values(*args), *args), "joint_zero", "controller's zero")
        got = 2.0 * right("ex09_puma_ik", "q4", *args)
        assert_named(judge("ex09_puma_ik", "q4", got, *args), "unnormalised", "direction", "length 2, not 1")


def test_a_standard_table_returned_unchanged_is_sent_to_lecture_02_section_8():
    """ex02 q4 rewrites a standard-DH table: returning it unchanged is the standard-DH mistake, told where the
    lecture compares the two conventions (§8); ex02 q3 keeps §5, the modified link matrix."""
    q = EXERCISES["ex02_dh_frames"].question("q4")
    for (table,) in q.public:
        verdict = judge("ex02_dh_frames", "q4", np.array(table), table)
        assert_named(verdict, "standard_dh", "lecture 02 §8")
        assert "§5" not in verdict.reason
    H, h, d2 = np.pi / 2, 0.8, 0.2
    standard = np.array([[H, 0.0, 0.0, h, 0], [H, 0.0, H, -d2, 0], [0.0, 0.0, 0.0, 0.0, 1]])
    assert_named(judge("ex02_dh_frames", "q3", standard, h, d2), "standard_dh", "lecture 02 §5")


# ---------------------------------------------------------------- issue 31: the class's other typical mistakes
def test_a_lock_threshold_other_than_the_question_s():
    """ex01 q6 states cos b < 1e-9: rotations 1.2e-10 and 1.5e-8 from the lock, each side, name another threshold."""
    q = EXERCISES["ex01_rotations"].question("q6")
    (Rs,) = q.public[2]  # inside the threshold, a general rotation, outside it

    def angles(R, tol):
        cb = np.hypot(R[0, 0], R[0, 1])
        if cb < tol or (tol == 0 and cb == 0):
            s = np.sign(R[0, 2])
            return [np.arctan2(s * R[1, 0], R[1, 1]), s * np.pi / 2, 0.0]
        return [np.arctan2(-R[1, 2], R[2, 2]), np.arctan2(R[0, 2], cb), np.arctan2(-R[0, 1], R[0, 0])]

    assert np.hypot(*Rs[0][0, :2]) < 1e-9 < np.hypot(*Rs[2][0, :2]) < 1e-7
    assert judge("ex01_rotations", "q6", [angles(R, 1e-9) for R in Rs], Rs).passed
    assert_named(judge("ex01_rotations", "q6", [angles(R, 1e-6) for R in Rs], Rs), "lock_threshold", "1.5e-8")
    assert_named(judge("ex01_rotations", "q6", [angles(R, 0.0) for R in Rs], Rs), "lock_threshold", "1.2e-10")


def test_the_arcsin_angle_and_other_turns_of_ex01_q2():
    u, v = np.array([1.0, 0.0, 0.0]), np.array([-1.0, 1.0, 0.0])  # 135° apart, the turn about e_z
    assert judge("ex01_rotations", "q2", rot("z", 3 * np.pi / 4), u, v).passed
    assert_named(judge("ex01_rotations", "q2", rot("z", np.pi / 4), u, v), "angle_quadrant", "arcsin", "90°")
    assert_named(judge("ex01_rotations", "q2", rot("x", 3 * np.pi / 4), u, v), "wrong_axis", "about u itself")
    K = skew([0.0, 0.0, 1.0])
    minus = np.eye(3) + np.sin(3 * np.pi / 4) * K - (1 - np.cos(3 * np.pi / 4)) * K @ K
    assert_named(judge("ex01_rotations", "q2", minus, u, v), "sign_flip", "Rodrigues' last term")


def test_a_height_left_out_of_a_table_a_factor_left_out_and_one_link_too_few():
    # ex04 q3: the MK3's shoulder is c + d1 above the rail frame: d1 alone leaves every pose c lower
    c, d1, a1, a2, a3, d5 = 450.0, 360.0, 135.0, 250.0, 215.0, 100.0
    h = np.pi / 2
    table = np.array([[-h, 0, 0, 0, 1], [h, 0, 0, c + d1, 0], [h, a1, 0, 0, 0], [0, a2, 0, 0, 0], [0, a3, 0, 0, 0],
                      [h, 0, 0, d5, 0]])  # fmt: skip
    assert judge("ex04_mk3_fk", "q3", table, c, d1, a1, a2, a3, d5).passed
    table[1, 3] = d1
    assert_named(judge("ex04_mk3_fk", "q3", table, c, d1, a1, a2, a3, d5), "missing_offset", "450 mm too low", "c")
    # ex09 q3: det J without the wrist's factor sin θ5 is det J_w
    L, q = (0.4318, 0.0203, 0.15005, 0.4318), np.array([0.3, 0.2, -0.4, 0.1, 0.9, 0.5])
    det = right("ex09_puma_ik", "q3", q, *L)
    assert_named(judge("ex09_puma_ik", "q3", det / np.sin(q[4]), q, *L), "missing_factor", "sin θ5")
    # ex03 q1: the product from row k + 2 on (one link too few)
    table, q, k = EXERCISES["ex03_puma_fk"].question("q1").public[0]
    T = right("ex03_puma_fk", "q1", np.asarray(table)[k + 1 :], np.asarray(q)[k + 1 :], 0)
    assert_named(judge("ex03_puma_fk", "q1", T, table, q, k), "off_by_one", "one link too late")

"""Written questions, marked by a person with a rubric (see :mod:`puma_course.grading.written`).

Keyed by exercise; each question's id continues the exercise's numbering (after q1 … q3 comes q4).
``prompt`` reaches the students (``puma-course release`` writes it into the exercise); ``criteria``,
``full_answer`` and ``worked`` never do: they are the marker's (``puma-course collect-written``).
"""

from __future__ import annotations

from puma_course.grading.written import Criterion, Written

FRAMES = Written(
    points=4,
    title="frames {1} and {2} of the RRP arm, justified",
    prompt=r"""
Take the RRP arm of question 3 at $q_1 = q_2 = 0$. **Sketch** the frames $\{0\}$, $\{1\}$ and $\{2\}$ on the arm
(a photo of a drawing, or a drawing made on screen, dragged into the answer cell below), **or describe** each
of them in words: where its origin is, and where its $z$ and $x$ axes point, in terms of $x_0, y_0, z_0$.

Then **justify** every placement by the rule of lecture 02 it follows, and say which choices the rules left
to you and which entries of your table those choices fixed. A sketch without the reasons earns at most half
the points.
""",
    criteria=(
        Criterion(
            "z axes",
            1,
            "z1 on the column's axis pointing up (q1 > 0 turns counter-clockwise seen from "
            "above); z2 on the shoulder axis pointing along -y0, because q2 > 0 raises the tip (right-hand "
            "rule); the sense of each z is the joint's positive sense, not a free choice",
        ),
        Criterion(
            "origin 1",
            1,
            "axes 1 and 2 intersect, at height h on the column: the origin of {1} is that "
            "crossing point, so a0 = 0, alpha0 = 0 and d1 = h (origin of {1} measured from {0} along z1)",
        ),
        Criterion(
            "origin 2",
            1,
            "axes 2 and 3 intersect where the boom's line crosses the shoulder axis, d2 "
            "from the column along +y0: the origin of {2} is there, a1 = 0, and the offset measured along "
            "z2 = -y0 is d = -d2 (the sign follows from the sense of z2)",
        ),
        Criterion(
            "x axes",
            1,
            "x1 and x2 along the common normals: x1 = ±(z1 × z2) (x1 = +x0 chosen so that "
            "theta1 has no offset), x2 = ±(z2 × z3) points up at q = 0, which gives theta2 the offset +90 "
            "deg and alpha1 = alpha2 = +90 deg; the free choices named are the signs of x1 and x2",
        ),
    ),
    full_answer=r"""
A sketch or a description of all three frames at $q_1 = q_2 = 0$, each placement with its rule: $z_i$ on joint
axis $i$ in its positive sense, the origin where the common normal of axes $i$ and $i+1$ meets axis $i$ (here
the axes intersect, so at the crossing point), $x_i$ along the common normal ($\pm z_i \times z_{i+1}$ when the
axes intersect). It names the free choices (the signs of $x_1$ and $x_2$) and the table entries they decide
($\theta_1$'s offset 0 and $\theta_2$'s offset $+90°$, the twists $+90°$), and it gets $d_2 = -d2$ with its sign.
""",
    worked=r"""
* $\{0\}$: given, on the floor, $z_0$ up, $x_0$ along the boom at $q = 0$.
* $z_1 = z_0$ (joint 1's axis, counter-clockwise from above is positive); $z_2 = -y_0$: a positive turn about
  $-y_0$ takes $x_0$ towards $+z_0$, which raises the tip, as $q_2 > 0$ must.
* Axes 1 and 2 meet at $(0, 0, h)$: origin of $\{1\}$ there, $a_0 = 0$, $\alpha_0 = 0$, $d_1 = h$.
  $x_1 = z_1 \times z_2 = z_0 \times (-y_0) = x_0$; choosing this sign keeps $\theta_1$ without offset.
* Axes 2 and 3 (the boom's line, $z_3$ along the boom outwards) meet at $(0, d_2, h)$: origin of $\{2\}$ there,
  $a_1 = 0$; from $\{1\}$'s origin it lies $d_2$ along $+y_0 = -z_2$, so $d = -d_2$. The twist from $z_1$ to
  $z_2$ about $x_1$ is $\alpha_1 = +90°$.
* $x_2 = z_2 \times z_3 = (-y_0) \times x_0 = z_0$ (up): from $x_1 = x_0$ to $x_2 = z_0$ about $z_2$ is $+90°$, the
  offset of $\theta_2$; the twist from $z_2$ to $z_3$ about $x_2$ is $\alpha_2 = +90°$.
* Free: the signs of $x_1$ and $x_2$ (the other signs give other, equally valid offsets and twists).
""",
)

POSITION_ENTRY = Written(
    points=5,
    title=r"one entry of ${}^0T_6$ of the robot on its pedestal, by hand",
    prompt=r"""
For the PUMA-560 on its pedestal, holding its tool, of question 2 (joint values $q$ counted as its controller
counts them), **derive by hand** the entry $p_z$ of ${}^0T_6$: the height of the tool's tip above the floor, as a
function of $q_1, \dots, q_6$ and $a_2, a_3, d_3, d_4, h, d_6$. Show the steps: which part of the product you need
and why the other joints drop out, how the controller's zero enters, and the identities you use to tidy the
result. Then **check** your expression at $q = 0$ against the picture. Write with LaTeX ($\cos(q_2 + q_3)$ may be
written $c_{23}$) or attach a photo of your working.
""",
    criteria=(
        Criterion(
            "split",
            1,
            "splits the tool's tip into the wrist centre plus d6 along z6: p_z = (0p4)_z + d6 "
            "(0z6)_z, or multiplies the six link matrices and says which entries it needs; explains why "
            "q1 (a turn about the vertical) and, for the wrist centre, q4, q5, q6 do not change its height",
        ),
        Criterion(
            "zero",
            1,
            "takes the controller's zero into account: theta2 = q2 - 90 deg, theta3 = q3 - 90 deg "
            "relative to lecture 03 (or a table with those offsets), and the base h below the shoulder",
        ),
        Criterion(
            "identities",
            1,
            "uses the sum-angle identities so that c2 c3 - s2 s3 = c23 (and the shifted "
            "angles: sin(q2 - 90 deg) = -cos q2, cos(q2 + q3 - 180 deg) = -c23)",
        ),
        Criterion(
            "result",
            1,
            "the right expression: p_z = h + a2 c2 + a3 s23 + d4 c23 + d6 (c23 c5 - s23 c4 s5), "
            "with c2 = cos q2, c23 = cos(q2 + q3) and so on",
        ),
        Criterion(
            "check",
            1,
            "checks at q = 0: p_z = h + a2 + d4 + d6, the arm and the tool straight up, as in "
            "the left picture (another checked pose counts too)",
        ),
    ),
    full_answer=r"""
The tip is the wrist centre plus $d_6$ along $z_6$; the wrist centre's height depends on $q_2, q_3$ only. With
the controller's zero ($\theta_2 = q_2 - 90°$, $\theta_3 = q_3 - 90°$) and the base $h$ below the shoulder, the
sum-angle identities give
$p_z = h + a_2 c_2 + a_3 s_{23} + d_4 c_{23} + d_6\,(c_{23} c_5 - s_{23} c_4 s_5)$, checked at $q = 0$:
$h + a_2 + d_4 + d_6$.
""",
    worked=r"""
1. ${}^0T_6 = {}^0T_1 \cdots {}^5T_6$. The tool's tip is the origin of $\{6\}$, $d_6$ beyond the wrist centre
   along $z_6$: $p = {}^0p_4 + d_6\, {}^0z_6$, so $p_z = ({}^0p_4)_z + d_6\, r_{33}$.
2. Lecture 03 (shoulder at the origin, its zero): $({}^0p_4)_z = -a_2 s_2 - a_3 s_{23} - d_4 c_{23}$ and
   $r_{33} = s_{23} c_4 s_5 - c_{23} c_5$, in the lecture's angles $\theta$; joint 1 turns about the vertical and
   joints 4-6 turn about the wrist centre, so neither changes its height.
3. The pedestal lifts everything by $h$; the controller counts $\theta_2 = q_2 - 90°$, $\theta_3 = q_3 - 90°$:
   $\sin\theta_2 = -\cos q_2$, $\theta_2 + \theta_3 = q_2 + q_3 - 180°$, so $s_{23} \to -s_{23}$, $c_{23} \to -c_{23}$.
4. $$p_z = h + a_2 c_2 + a_3 s_{23} + d_4 c_{23} + d_6\,(c_{23} c_5 - s_{23} c_4 s_5).$$
5. At $q = 0$: $p_z = h + a_2 + d_4 + d_6$, the straight-up arm of the picture. (At $q_2 = 90°$, the rest 0:
   $h + a_3$, the upper arm horizontal and the forearm and tool pointing sideways.)
""",
)

PORTER_COUNT = Written(
    points=4,
    title="how many configurations the telescopic rod leaves, and why",
    prompt=r"""
Question 2's chain has a telescopic rod: a fixed part $l_2$ plus the stroke $q_2 \ge 0$, so that
$|p_3 - p_2| = l_2 + q_2$. Take its first public case: the hand frame that Porter's chain with
$(l_1, l_3, l_4) = (1, 0.5, 0.3)$ takes at $q = (0.3, 0.7, 1.3, -0.4, 0.9, 0.6)$, and $l_2 = 1.6$.

1. **How many** configurations of the telescopic-rod chain reach this hand frame? **Justify** the number from
   the rod lengths $|p_3 - p_2|$ that Porter's four configurations of it need (give them, to 3 decimals).
2. The configurations drop out **in pairs**. Which configurations (arm-plane side, sign of $c_4$) form each pair,
   and why must a pair always stay or go together?
3. Keep the hand frame and change $l_2$: for which $l_2$ do all four configurations remain, for which two, and
   for which is the hand frame out of reach?
4. Lecture 06 §4 finds a singular family at zero stroke ($\alpha_2$ free). What becomes of it on this chain? What
   happens at this hand frame when $l_2$ equals the shorter rod length you found?

Answer in a few sentences each; a sketch is welcome.
""",
    criteria=(
        Criterion(
            "two remain",
            1,
            "two: Porter's four configurations need rod lengths 1.300 (twice) and 1.924 (twice); with l2 = 1.6 "
            "the shorter would need the stroke q2 = -0.300 < 0 (dropped), the longer has q2 = 0.324 (kept)",
        ),
        Criterion(
            "pairs",
            1,
            "each pair shares its points p0 ... p5 (the two sides of the arm plane give the same points), hence "
            "its rod length: (front, c4 > 0) with (back, c4 < 0) at 1.300, (front, c4 < 0) with (back, c4 > 0) at "
            "1.924 (the back side turns the frame, so the same rod direction has the other sign of c4)",
        ),
        Criterion(
            "range of l2",
            1,
            "all four for l2 <= 1.300, two for 1.300 < l2 <= 1.924, none (out of reach) for l2 > 1.924: the count "
            "is 4, 2 or 0, never odd",
        ),
        Criterion(
            "no zero-stroke family",
            1,
            "the family needs p3 = p2 (a rod of length 0); here |p3 - p2| >= l2 > 0, so alpha2 is always "
            "fixed by the rod's direction and the family is gone; at l2 = 1.300 the pair's stroke is 0, the "
            "stroke's end: both configurations remain (q2 = 0 is allowed), four in all, none singular",
        ),
    ),
    full_answer=r"""
Two: the four configurations need rods of $1.300$ and $1.924$ (each twice), and only the longer exceeds
$l_2 = 1.6$; the pairs are the two sides of the arm plane with the same points ((front, $c_4 > 0$) with
(back, $c_4 < 0$); (front, $c_4 < 0$) with (back, $c_4 > 0$)); four for $l_2 \le 1.300$, two up to $1.924$,
none beyond; the zero-stroke family needs a rod of length 0, which $l_2 > 0$ rules out: $q_2 = 0$ is only the
stroke's end.
""",
    worked=r"""
1. Two. Porter's four configurations of this hand frame have the rod lengths $|p_3 - p_2| = 1.300$,
   $1.924$, $1.924$, $1.300$ (his $q_2$, from `Porter(1, 0.5, 0.3).ik(T)`); the telescopic chain needs the
   stroke $q_2 = |p_3 - p_2| - l_2$, which is $-0.300 < 0$ for the first pair (the rod would have to be shorter
   than its fixed part) and $0.324 \ge 0$ for the second. So front/$c_4 < 0$ and back/$c_4 > 0$ remain.
2. The other side of the arm plane ($\alpha_1 + \pi$) turns the column by $\pi$ and every later frame with it,
   but leaves the points $p_0, \dots, p_5$ where they are: the same $p_2$, the same $p_3$, the same rod length.
   The turned frames reverse the sign of $c_4$ for the same rod direction, so (front, $c_4 > 0$) pairs with
   (back, $c_4 < 0$) at $1.300$, and (front, $c_4 < 0$) with (back, $c_4 > 0$) at $1.924$. A pair has one stroke,
   so it stays or goes as a whole: away from singular poses the count is 4, 2 or 0.
3. All four for $l_2 \le 1.300$, two for $1.300 < l_2 \le 1.924$, none for $l_2 > 1.924$ (the rod's fixed
   part is longer than either point sequence allows).
4. Lecture 06's family needs $p_3 = p_2$: a rod of length zero, whose direction then does not matter. Here the
   rod is never shorter than $l_2 > 0$, so its direction, and $\alpha_2$ with it, is always fixed: the family
   is gone. At $l_2 = 1.300$ the first pair needs $q_2 = 0$: the slide at the end of its stroke, allowed, and
   nothing singular about it; four configurations reach the hand frame.
""",
)

WRITTEN = {
    "ex02_dh_frames": (FRAMES,),
    "ex03_puma_fk": (POSITION_ENTRY,),
    "ex06_porter_explicit": (PORTER_COUNT,),
}

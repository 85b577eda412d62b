// node --test: the viewer's geometry helpers (js/src/geometry.js), against values worked out by hand.
import assert from "node:assert/strict";
import { test } from "node:test";

import { allInView, boundingSphere, fitDistance, formatLength, frameAt, gridLines, niceStep, orbitPosition, pointAt, reframe, segmentPlacement } from "../src/geometry.js";

const close = (a, b, tol = 1e-12) => a.forEach((x, i) => assert.ok(Math.abs(x - b[i]) <= tol, `${a} != ${b}`));

function rotate(q, v) {
  // v' = v + 2w (u x v) + 2 u x (u x v), u = (x, y, z)
  const [x, y, z, w] = q;
  const c1 = [y * v[2] - z * v[1], z * v[0] - x * v[2], x * v[1] - y * v[0]];
  const c2 = [y * c1[2] - z * c1[1], z * c1[0] - x * c1[2], x * c1[1] - y * c1[0]];
  return [0, 1, 2].map((i) => v[i] + 2 * w * c1[i] + 2 * c2[i]);
}

test("frames and points are read from flat row-major arrays", () => {
  const flat = [...Array(32).keys()];
  assert.deepEqual(frameAt(flat, 1), [...Array(16).keys()].map((i) => i + 16));
  assert.deepEqual(pointAt([0, 1, 2, 3, 4, 5], 1), [3, 4, 5]);
});

test("a segment's cylinder turns +y onto the segment, for every direction", () => {
  const cases = [[1, 0, 0], [0, 1, 0], [0, 0, -2], [0, -1, 0], [1, 1, 1], [-0.3, 0.2, 0.9]];
  for (const d of cases) {
    const s = segmentPlacement([1, 2, 3], [1 + d[0], 2 + d[1], 3 + d[2]]);
    const L = Math.hypot(...d);
    assert.ok(Math.abs(s.length - L) < 1e-12);
    close(s.mid, [1 + d[0] / 2, 2 + d[1] / 2, 3 + d[2] / 2]);
    close(rotate(s.quaternion, [0, 1, 0]), d.map((x) => x / L), 1e-12);
    assert.ok(Math.abs(Math.hypot(...s.quaternion) - 1) < 1e-12);
  }
});

test("a zero-length segment has length 0 and no rotation (the viewer hides it)", () => {
  assert.deepEqual(segmentPlacement([1, 1, 1], [1, 1, 1]), { mid: [1, 1, 1], length: 0, quaternion: [0, 0, 0, 1] });
});

test("grid steps are 1, 2 or 5 times a power of ten", () => {
  assert.equal(niceStep(2.0), 0.2);
  assert.equal(niceStep(1600), 200);
  assert.equal(niceStep(3.6), 0.5);
  assert.equal(niceStep(0), 1);
});

test("orbit position: azimuth from +x towards +y, elevation above the xy plane", () => {
  close(orbitPosition([0, 0, 0], 2, 0, 0), [2, 0, 0]);
  close(orbitPosition([1, 1, 1], 2, 90, 0), [1, 3, 1]);
  close(orbitPosition([0, 0, 0], 2, 0, 90), [0, 0, 2], 1e-12);
});

test("a sphere fits the narrower angle of the view", () => {
  // fov 90° (half 45°), square view: d = r / sin 45°
  assert.ok(Math.abs(fitDistance(1, 90, 1, 1) - Math.SQRT2) < 1e-12);
  assert.ok(fitDistance(1, 90, 0.5, 1) > fitDistance(1, 90, 2, 1)); // a tall, narrow view needs more distance
});

test("grid lines: 2n + 1 in each direction, at height z, snapped to the step", () => {
  const lines = gridLines([0.04, 0, 0], 2, 0.5, -0.3);
  assert.equal(lines.length, 2 * 5);
  assert.ok(lines.every(([a, b]) => a[2] === -0.3 && b[2] === -0.3));
  assert.deepEqual(lines[0], [[-1, -1, -0.3], [-1, 1, -0.3]]);
});

test("lengths with their unit", () => {
  assert.equal(formatLength(0.2, "m"), "0.2 m");
  assert.equal(formatLength(100, "mm"), "100 mm");
  assert.equal(formatLength(0.30000000000000004, ""), "0.3");
});

test("the bounding sphere of a pose: box centre, farthest point, plus the pad", () => {
  const { center, radius } = boundingSphere([[0, 0, 0], [2, 0, 0], [1, 1, 0]], 0.5);
  close(center, [1, 0.5, 0]);
  assert.ok(Math.abs(radius - (Math.hypot(1, 0.5) + 0.5)) < 1e-12);
});

test("points are in view inside the picture's margin and in front of the camera only", () => {
  assert.equal(allInView([[0, 0, 0.5], [0.9, -0.9, 0.99]]), true);
  assert.equal(allInView([[0.96, 0, 0.5]]), false);
  assert.equal(allInView([[0, -1.2, 0.5]]), false);
  assert.equal(allInView([[0, 0, 1.2]]), false); // behind the camera
  assert.equal(allInView([[0.96, 0, 0.5]], 0.97), true);
});

test("reframing keeps the direction of view and fits the sphere", () => {
  // looking from +x at the origin, 10 away; the arm now fills a sphere of radius 2 around (0, 5, 1)
  const r = reframe([10, 0, 0], [0, 0, 0], { center: [0, 5, 1], radius: 2 }, 30, 1.5);
  close(r.target, [0, 5, 1]);
  const dist = fitDistance(2, 30, 1.5);
  close(r.position, [dist, 5, 1], 1e-12);
  // a turned view (from above and to the side) stays turned: the same unit direction
  const p = [3, -4, 12];
  const s = reframe(p, [0, 0, 0], { center: [1, 1, 1], radius: 1 }, 40, 1);
  const d = s.position.map((x, k) => x - s.target[k]);
  const n = Math.hypot(...d);
  close(d.map((x) => x / n), [3 / 13, -4 / 13, 12 / 13], 1e-12);
  assert.ok(Math.abs(n - fitDistance(1, 40, 1)) < 1e-12);
});

// The viewer's small pieces of geometry, kept free of three.js so node --test can check them
// (js/test/geometry.test.mjs). Poses arrive from the kernel as row-major 4x4 transforms,
// flattened (16 numbers per frame), mapping a frame's coordinates into the base frame's.

/** The k-th 4x4 transform of a flat row-major array, as 16 numbers (row-major). */
export function frameAt(flat, k) {
  return Array.prototype.slice.call(flat, 16 * k, 16 * k + 16);
}

/** The k-th point (x, y, z) of a flat array of points. */
export function pointAt(flat, k) {
  return [flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]];
}

/**
 * A link segment from p to q as a unit cylinder (along +y, height 1, centred at the origin) is
 * placed: its midpoint, its length and the unit quaternion [x, y, z, w] turning +y onto q - p.
 * A segment shorter than `eps` has length 0 and the identity rotation (the viewer hides it).
 */
export function segmentPlacement(p, q, eps = 1e-12) {
  const d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
  const length = Math.hypot(d[0], d[1], d[2]);
  const mid = [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2];
  if (!(length > eps)) return { mid, length: 0, quaternion: [0, 0, 0, 1] };
  const u = [d[0] / length, d[1] / length, d[2] / length];
  // the rotation from y = (0, 1, 0) to u: axis y x u = (u_z, 0, -u_x), angle acos(u_y)
  const c = u[1];
  if (c < -1 + 1e-12) return { mid, length, quaternion: [1, 0, 0, 0] }; // half a turn about x
  const s = Math.sqrt(2 * (1 + c));
  return { mid, length, quaternion: [u[2] / s, 0, -u[0] / s, s / 2] };
}

/** A "nice" grid step (1, 2 or 5 times a power of ten) giving about `lines` lines over `span`. */
export function niceStep(span, lines = 10) {
  if (!(span > 0) || !Number.isFinite(span)) return 1;
  const raw = span / lines;
  const p = 10 ** Math.floor(Math.log10(raw));
  const m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

/**
 * Camera position for an orbit view of `center` from `distance`, at azimuth and elevation in
 * degrees (matplotlib's convention: azimuth from +x towards +y, elevation above the xy plane;
 * z is up).
 */
export function orbitPosition(center, distance, azimDeg, elevDeg) {
  const a = (azimDeg * Math.PI) / 180;
  const e = (elevDeg * Math.PI) / 180;
  return [
    center[0] + distance * Math.cos(e) * Math.cos(a),
    center[1] + distance * Math.cos(e) * Math.sin(a),
    center[2] + distance * Math.sin(e),
  ];
}

/**
 * The distance at which a sphere of `radius` just fits a perspective view of vertical field of
 * view `fovDeg` and width/height `aspect` (the narrower of the two angles decides), times `margin`.
 */
export function fitDistance(radius, fovDeg, aspect, margin = 1.05) {
  const half = (fovDeg * Math.PI) / 360;
  const halfH = Math.atan(Math.tan(half) * Math.min(aspect, 1));
  return (margin * radius) / Math.sin(Math.min(half, halfH));
}

/** The grid lines (pairs of endpoints) of a square grid of side `size` and spacing `step` at height z. */
export function gridLines(center, size, step, z) {
  const n = Math.max(1, Math.round(size / step / 2));
  const half = n * step;
  const cx = Math.round(center[0] / step) * step;
  const cy = Math.round(center[1] / step) * step;
  const lines = [];
  for (let i = -n; i <= n; i += 1) {
    lines.push([[cx + i * step, cy - half, z], [cx + i * step, cy + half, z]]);
    lines.push([[cx - half, cy + i * step, z], [cx + half, cy + i * step, z]]);
  }
  return lines;
}

/** Text for a length with its unit: "0.1 m", "50 mm", "0.2" (unitless). */
export function formatLength(value, units) {
  const v = Number.parseFloat(value.toPrecision(6)).toString();
  return units ? `${v} ${units}` : v;
}

/**
 * The sphere a view must hold: centred on the bounding box of `points` ([x, y, z] each), its
 * radius the farthest point's distance plus `pad` (e.g. the longest triad).
 */
export function boundingSphere(points, pad = 0) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (const p of points) {
    for (let k = 0; k < 3; k += 1) {
      lo[k] = Math.min(lo[k], p[k]);
      hi[k] = Math.max(hi[k], p[k]);
    }
  }
  const center = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
  let radius = 0;
  for (const p of points) radius = Math.max(radius, Math.hypot(p[0] - center[0], p[1] - center[1], p[2] - center[2]));
  return { center, radius: Math.max(radius + pad, 1e-9) };
}

/**
 * Whether every point, given in normalized device coordinates ([x, y, z], the view's box is
 * [-1, 1] on each), lies in front of the camera and within `limit` of the picture's edges.
 */
export function allInView(ndc, limit = 0.95) {
  return ndc.every(([x, y, z]) => z > -1 && z < 1 && Math.abs(x) <= limit && Math.abs(y) <= limit);
}

/**
 * The camera that frames `sphere` ({center, radius}) from the direction it looks now: the
 * target moves to the sphere's centre and the camera back along its own line of sight to the
 * distance that fits the sphere (fitDistance), so a view the user turned stays turned.
 */
export function reframe(position, target, sphere, fovDeg, aspect) {
  const d = [0, 1, 2].map((k) => position[k] - target[k]);
  const n = Math.hypot(...d) || 1;
  const dist = fitDistance(sphere.radius, fovDeg, aspect);
  return { target: [...sphere.center], position: sphere.center.map((c, k) => c + (d[k] / n) * dist) };
}

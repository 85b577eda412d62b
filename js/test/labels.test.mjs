// node --test: the label placement of the viewer (js/src/labels.js), checked against rectangles worked out by hand.
import assert from "node:assert/strict";
import { test } from "node:test";

import { candidateRect, overlaps, placeLabels } from "../src/labels.js";

const apart = (a, b) => !overlaps(a, b);

test("a lone label sits north-east of its anchor, gap pixels away", () => {
  const [r] = placeLabels([{ x: 100, y: 100, w: 30, h: 14 }], { gap: 4 });
  assert.deepEqual(r, { x: 104, y: 82, w: 30, h: 14, leader: false });
});

test("candidate rectangles in the eight directions", () => {
  assert.deepEqual(candidateRect(50, 50, 20, 10, -1, 1, 5), { x: 25, y: 55, w: 20, h: 10 });
  assert.deepEqual(candidateRect(50, 50, 20, 10, 0, -1, 5), { x: 40, y: 35, w: 20, h: 10 });
});

test("labels of frames at one point ({4}, {5}, {6} at the wrist) never overlap and stay near it", () => {
  const items = [0, 1, 2, 3].map(() => ({ x: 200, y: 150, w: 28, h: 15 }));
  const spots = placeLabels(items, { bounds: { width: 400, height: 300 } });
  for (let i = 0; i < spots.length; i += 1) {
    for (let j = i + 1; j < spots.length; j += 1) assert.ok(apart(spots[i], spots[j]), `${i} and ${j} overlap`);
    const cx = spots[i].x + spots[i].w / 2;
    const cy = spots[i].y + spots[i].h / 2;
    assert.ok(Math.hypot(cx - 200, cy - 150) < 40, "a label wandered off");
  }
  assert.deepEqual(spots.map((s) => s.leader), [false, false, false, false]);
});

test("a crowd of labels on one spot: all placed without overlap, the far ones get a leader line", () => {
  const items = Array.from({ length: 12 }, () => ({ x: 200, y: 150, w: 30, h: 15 }));
  const spots = placeLabels(items);
  for (let i = 0; i < spots.length; i += 1) {
    for (let j = i + 1; j < spots.length; j += 1) assert.ok(apart(spots[i], spots[j]), `${i} and ${j} overlap`);
  }
  assert.ok(spots.some((s) => s.leader));
});

test("a label does not cover another frame's anchor", () => {
  // anchor B sits exactly where A's first choice (north-east) would be
  const spots = placeLabels([{ x: 100, y: 100, w: 30, h: 14 }, { x: 115, y: 90, w: 30, h: 14 }]);
  const b = { x: 113, y: 88, w: 4, h: 4 };
  assert.ok(apart(spots[0], b));
});

test("labels stay inside the view when they can", () => {
  const [r] = placeLabels([{ x: 395, y: 5, w: 30, h: 14 }], { bounds: { width: 400, height: 300 } });
  assert.ok(r.x >= 0 && r.y >= 0 && r.x + r.w <= 400 && r.y + r.h <= 300, JSON.stringify(r));
});

test("invisible items (behind the camera) get null and take no room", () => {
  const spots = placeLabels([{ x: 10, y: 10, w: 5, h: 5, visible: false }, { x: 10, y: 10, w: 5, h: 5 }]);
  assert.equal(spots[0], null);
  assert.equal(spots[1].leader, false);
});

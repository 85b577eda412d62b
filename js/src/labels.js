// Placing the frame labels {i} on the screen so they stay readable and never overlap.
//
// Pure functions (no DOM, no three.js): node --test checks them (js/test/labels.test.mjs).
// Coordinates are CSS pixels, x to the right and y downwards, as in the page.

/** Where a label may sit around its anchor, tried in this order: NE, E, SE, NW, W, SW, N, S. */
export const DIRECTIONS = [
  [1, -1], [1, 0], [1, 1], [-1, -1], [-1, 0], [-1, 1], [0, -1], [0, 1],
];

/** True when two rectangles {x, y, w, h} overlap by more than `pad` pixels' slack. */
export function overlaps(a, b, pad = 0) {
  return a.x < b.x + b.w + pad && b.x < a.x + a.w + pad && a.y < b.y + b.h + pad && b.y < a.y + a.h + pad;
}

/** The rectangle of a w x h label put in direction (dx, dy) at `gap` pixels from the anchor (ax, ay). */
export function candidateRect(ax, ay, w, h, dx, dy, gap) {
  const x = dx > 0 ? ax + gap : dx < 0 ? ax - gap - w : ax - w / 2;
  const y = dy > 0 ? ay + gap : dy < 0 ? ay - gap - h : ay - h / 2;
  return { x, y, w, h };
}

function inside(r, bounds) {
  return !bounds || (r.x >= 0 && r.y >= 0 && r.x + r.w <= bounds.width && r.y + r.h <= bounds.height);
}

function overlapArea(a, b) {
  const w = Math.min(a.x + a.w, b.x + b.w) - Math.max(a.x, b.x);
  const h = Math.min(a.y + a.h, b.y + b.h) - Math.max(a.y, b.y);
  return w > 0 && h > 0 ? w * h : 0;
}

/**
 * Place labels next to their anchors without overlaps.
 *
 * items: [{x, y, w, h, visible?}] (anchor in pixels, label size); earlier items win (give the
 * base and the tool first). Each label tries the eight directions at `gap` pixels, then at
 * growing distances (rings of `step` pixels, up to `rings`), and takes the first spot that
 * overlaps no placed label, covers no other anchor and stays inside `bounds` ({width, height}).
 * When no spot is free it takes the one with the least overlap. Returns, per item,
 * {x, y, w, h, leader} (top-left corner; `leader` is true when the label sits past the first
 * ring, so a thin line should join it to its anchor) or null for an invisible item.
 */
export function placeLabels(items, { gap = 4, step = 14, rings = 5, pad = 1, bounds = null } = {}) {
  const placed = [];
  const out = [];
  const anchors = items.map((it) => ({ x: it.x - 2, y: it.y - 2, w: 4, h: 4, visible: it.visible !== false }));
  items.forEach((it, k) => {
    if (it.visible === false) {
      out.push(null);
      return;
    }
    let best = null;
    let bestCost = Infinity;
    for (let ring = 0; ring <= rings && bestCost > 0; ring += 1) {
      for (const [dx, dy] of DIRECTIONS) {
        const r = candidateRect(it.x, it.y, it.w, it.h, dx, dy, gap + ring * step);
        let cost = 0;
        for (const p of placed) cost += overlapArea(r, { x: p.x - pad, y: p.y - pad, w: p.w + 2 * pad, h: p.h + 2 * pad });
        anchors.forEach((a, j) => {
          if (j !== k && a.visible) cost += overlapArea(r, a);
        });
        if (!inside(r, bounds)) cost += 0.5 * r.w * r.h;
        if (cost < bestCost) {
          best = { ...r, leader: ring > 0 };
          bestCost = cost;
          if (cost === 0) break;
        }
      }
    }
    placed.push(best);
    out.push(best);
  });
  return out;
}

// The anywidget front end of puma_course.viz.viewer.Viewer: a three.js (WebGL) view of an arm.
//
// The kernel sends the scene once (`scene`: frame styles and labels, view, grid) and then only
// what moves (`pose`: the frames and the link polyline, flat row-major numbers); ghosts,
// targets and an animation are separate traits. Rendering happens on demand (a change of the
// pose or of the camera), never in a loop. Each container carries `__puma` (render counts and
// times) for the browser tests and the latency benchmark.
import {
  AmbientLight,
  BufferGeometry,
  Color,
  ConeGeometry,
  CylinderGeometry,
  DirectionalLight,
  Float32BufferAttribute,
  Group,
  LineBasicMaterial,
  LineDashedMaterial,
  LineSegments,
  Line,
  Matrix4,
  Mesh,
  MeshLambertMaterial,
  PerspectiveCamera,
  Scene,
  SphereGeometry,
  Vector3,
  WebGLRenderer,
} from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

import {
  allInView,
  boundingSphere,
  fitDistance,
  formatLength,
  frameAt,
  gridLines,
  niceStep,
  orbitPosition,
  pointAt,
  reframe,
  segmentPlacement,
} from "./geometry.js";
import { placeLabels } from "./labels.js";

const AXIS_COLORS = [0xd62728, 0x2ca02c, 0x1f77b4]; // x red, y green, z blue (matplotlib's tab colours)
const FOV = 35;
const KEY_HELP = "arrow keys turn, + and - zoom, 0 resets";
const TURN = 10; // degrees per arrow key

const CSS = `
.puma-viewer { position: relative; overflow: hidden; background: #fbfbfb; border: 1px solid #ddd; border-radius: 4px; }
.puma-viewer canvas { display: block; outline: none; }
.puma-viewer canvas:focus-visible { outline: 3px solid #1a5fb4; outline-offset: -3px; }
.puma-viewer .puma-status { position: absolute; width: 1px; height: 1px; overflow: hidden; clip: rect(0 0 0 0); white-space: nowrap; }
.puma-viewer .puma-labels { position: absolute; inset: 0; pointer-events: none; }
.puma-viewer .puma-label { position: absolute; font: 600 13px/1 system-ui, sans-serif; color: #222; white-space: nowrap;
  padding: 1px 3px; background: rgba(255, 255, 255, 0.82); border-radius: 3px; }
.puma-viewer .puma-label.faint { color: #595959; font-weight: 400; }
.puma-viewer .puma-label.target { color: #8a2be2; }
.puma-viewer svg.puma-leaders { position: absolute; inset: 0; pointer-events: none; }
.puma-viewer .puma-bar { position: absolute; top: 6px; right: 6px; display: flex; gap: 4px; align-items: center; }
.puma-viewer .puma-bar button { font: 12px system-ui, sans-serif; padding: 2px 8px; cursor: pointer;
  background: #fff; border: 1px solid #bbb; border-radius: 3px; }
.puma-viewer .puma-title { position: absolute; top: 6px; left: 8px; font: 600 13px system-ui, sans-serif; color: #333; }
.puma-viewer .puma-legend { position: absolute; bottom: 6px; left: 8px; font: 11px system-ui, sans-serif; color: #555; }
.puma-viewer .puma-player { display: flex; gap: 6px; align-items: center; font: 11px system-ui, sans-serif; color: #555; }
`;

function ensureStyle() {
  if (document.getElementById("puma-viewer-style")) return;
  const style = document.createElement("style");
  style.id = "puma-viewer-style";
  style.textContent = CSS;
  document.head.appendChild(style);
}

function setMatrix(object, flat16) {
  object.matrix.set(...flat16); // Matrix4.set takes row-major arguments
  object.matrixWorldNeedsUpdate = true;
}

function lineGeometry(points) {
  const g = new BufferGeometry();
  g.setAttribute("position", new Float32BufferAttribute(points.flat(), 3));
  return g;
}

/** One triad: three arrows (shaft and head) along the frame's x, y, z, and optionally its z axis dashed. */
function makeTriad(length, { opacity = 1, axis = false, shaft = 0.035 } = {}) {
  const group = new Group();
  group.matrixAutoUpdate = false;
  const transparent = opacity < 1;
  const r = shaft * length;
  const shaftGeom = new CylinderGeometry(r, r, 0.8 * length, 8);
  const headGeom = new ConeGeometry(2.6 * r, 0.2 * length, 12);
  const turns = [
    new Matrix4().makeRotationZ(-Math.PI / 2), // +y onto +x
    new Matrix4(),
    new Matrix4().makeRotationX(Math.PI / 2), // +y onto +z
  ];
  for (let k = 0; k < 3; k += 1) {
    const mat = new MeshLambertMaterial({ color: AXIS_COLORS[k], transparent, opacity });
    const s = new Mesh(shaftGeom, mat);
    s.applyMatrix4(new Matrix4().makeTranslation(0, 0.4 * length, 0).premultiply(turns[k]));
    const h = new Mesh(headGeom, mat);
    h.applyMatrix4(new Matrix4().makeTranslation(0, 0.9 * length, 0).premultiply(turns[k]));
    group.add(s, h);
  }
  if (axis) {
    const line = new Line(
      lineGeometry([[0, 0, -1.1 * length], [0, 0, 1.1 * length]]),
      new LineDashedMaterial({ color: 0x1f77b4, dashSize: 0.08 * length, gapSize: 0.06 * length, transparent: true, opacity: 0.7 }),
    );
    line.computeLineDistances();
    group.add(line);
  }
  return group;
}

/** Free the GPU memory of everything under a group, then empty it (ghosts and targets are rebuilt when they change). */
function disposeChildren(group) {
  group.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
    if (o.material) o.material.dispose();
  });
  group.clear();
}

/** The links of one arm: a cylinder per segment of the polyline and a ball at each vertex. */
class Links {
  constructor(count, radius, color, opacity = 1) {
    this.group = new Group();
    const transparent = opacity < 1;
    const mat = new MeshLambertMaterial({ color, transparent, opacity, depthWrite: !transparent });
    const jointMat = new MeshLambertMaterial({ color: 0x555555, transparent, opacity, depthWrite: !transparent });
    const cyl = new CylinderGeometry(radius, radius, 1, 16);
    const ball = new SphereGeometry(1.35 * radius, 16, 12);
    this.segments = [];
    this.balls = [];
    for (let k = 0; k < count; k += 1) {
      const b = new Mesh(ball, jointMat);
      this.balls.push(b);
      this.group.add(b);
      if (k + 1 < count) {
        const m = new Mesh(cyl, mat);
        this.segments.push(m);
        this.group.add(m);
      }
    }
  }

  update(points) {
    const pts = this.balls.map((_, k) => pointAt(points, k));
    pts.forEach((p, k) => this.balls[k].position.set(p[0], p[1], p[2]));
    this.segments.forEach((m, k) => {
      const s = segmentPlacement(pts[k], pts[k + 1]);
      m.visible = s.length > 0;
      m.position.set(...s.mid);
      m.quaternion.set(...s.quaternion);
      m.scale.set(1, Math.max(s.length, 1e-9), 1);
    });
  }

  setOpacity(opacity) {
    for (const m of [...this.segments, ...this.balls]) {
      m.material.opacity = opacity;
      m.material.transparent = opacity < 1;
      m.material.depthWrite = opacity >= 1;
    }
  }
}

function render({ model, el }) {
  ensureStyle();
  const sceneSpec = model.get("scene");
  const height = model.get("height") || 420;
  const box = document.createElement("div");
  box.className = "puma-viewer";
  box.style.height = `${height}px`;
  box.style.width = "100%";
  el.appendChild(box);

  const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xfbfbfb);
  box.appendChild(renderer.domElement);
  // the canvas is reached by Tab and turned by keys; a polite live region says where the tool is (issue 34)
  const canvas = renderer.domElement;
  canvas.tabIndex = 0;
  canvas.setAttribute("role", "application");
  canvas.setAttribute("aria-roledescription", "3-D view");
  canvas.setAttribute("aria-label", `3-D view of ${sceneSpec.title || "the arm"}: ${KEY_HELP}; or drag to turn, wheel to zoom`);
  canvas.setAttribute("data-lm-suppress-shortcuts", "true");

  const leaders = document.createElementNS("http://www.w3.org/2000/svg", "svg");
  leaders.setAttribute("class", "puma-leaders");
  leaders.setAttribute("aria-hidden", "true");
  const labelLayer = document.createElement("div");
  labelLayer.className = "puma-labels";
  labelLayer.setAttribute("aria-hidden", "true"); // the frame names drawn over the view: the live region speaks
  box.append(leaders, labelLayer);

  if (sceneSpec.title) {
    const t = document.createElement("div");
    t.className = "puma-title";
    t.textContent = sceneSpec.title;
    box.appendChild(t);
  }

  const scene = new Scene();
  scene.background = new Color(0xfbfbfb);
  const camera = new PerspectiveCamera(FOV, 1, 1e-3, 1e3);
  camera.up.set(0, 0, 1);
  scene.add(new AmbientLight(0xffffff, 1.6));
  const sun = new DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, 0.5, 2);
  camera.add(sun);
  scene.add(camera);

  // the sphere the starting view frames: the scene's, or an animation's (all its poses); "reset
  // view" frames the pose shown at that moment instead (an arm moved out of view comes back)
  let home = { center: sceneSpec.center, radius: sceneSpec.radius };
  let animView = null;
  const radius = sceneSpec.radius;
  const near = radius / 100;
  camera.near = near;
  camera.far = radius * 100;

  // ground grid
  const grid = sceneSpec.grid;
  const step = grid.step || niceStep(grid.size);
  const lines = gridLines(grid.center || sceneSpec.center, grid.size, step, grid.z);
  const gridGeom = lineGeometry(lines.flat());
  scene.add(new LineSegments(gridGeom, new LineBasicMaterial({ color: 0xb8b8b8, transparent: true, opacity: 0.8 })));
  const legend = document.createElement("div");
  legend.className = "puma-legend";
  legend.textContent = `grid ${formatLength(step, sceneSpec.units)}${sceneSpec.note ? ` · ${sceneSpec.note}` : ""}`;
  box.appendChild(legend);

  // the arm: links and one triad per frame
  const styles = sceneSpec.frames;
  const links = new Links(sceneSpec.points, sceneSpec.link.radius, new Color(sceneSpec.link.color).getHex());
  scene.add(links.group);
  const triads = styles.map((s) => {
    const g = makeTriad(s.length, { opacity: s.faint ? 0.3 : 1, axis: Boolean(s.axis) });
    g.visible = s.triad !== false;
    scene.add(g);
    return g;
  });
  const labels = styles.map((s) => {
    const d = document.createElement("div");
    d.className = `puma-label${s.faint ? " faint" : ""}`;
    d.textContent = s.label || "";
    d.style.display = s.label ? "" : "none";
    labelLayer.appendChild(d);
    return d;
  });

  // ghosts (IK solutions) and targets are rebuilt when they change (rarely)
  const ghostGroup = new Group();
  const targetGroup = new Group();
  scene.add(ghostGroup, targetGroup);
  let ghostArms = [];
  let targetLabels = [];

  // what was drawn, for the browser tests: counts and times, the frames' origins as drawn, labels' boxes
  const stats = { renders: 0, poseRenders: 0, lastRender: 0, lastPoseRender: 0, lastPoseMessage: 0, poseSeq: -1,
    labels: [], origins: [], ghosts: 0, selected: -1, animStep: -1, animSteps: 0, reframes: 0, keyTurns: 0, status: "" };
  box.__puma = stats;
  box.dataset.poseRenders = "0";

  let pending = false;
  let poseDirty = false;
  let started = false; // the first view is set once the box has its size on the page
  let pose = model.get("pose");

  function applyPose(p) {
    pose = p;
    links.update(p.points);
    triads.forEach((g, k) => setMatrix(g, frameAt(p.frames, k)));
    poseDirty = true;
  }

  function placeAllLabels(width, heightPx) {
    const items = [];
    const nodes = [];
    const v = new Vector3();
    const addItem = (node, xyz, visible) => {
      v.set(xyz[0], xyz[1], xyz[2]).project(camera);
      const onScreen = visible && v.z < 1 && v.z > -1;
      items.push({ x: ((v.x + 1) / 2) * width, y: ((1 - v.y) / 2) * heightPx, w: node.offsetWidth, h: node.offsetHeight,
        visible: onScreen });
      nodes.push(node);
    };
    // base and tool first (they win the best spots), then the others in order, then targets
    const order = styles.map((_, k) => k).sort((a, b) => (styles[b].priority || 0) - (styles[a].priority || 0));
    for (const k of order) {
      const f = frameAt(pose.frames, k);
      addItem(labels[k], [f[3], f[7], f[11]], Boolean(styles[k].label) && triads[k].visible);
    }
    targetLabels.forEach(({ node, xyz }) => addItem(node, xyz, true));
    const spots = placeLabels(items, { bounds: { width, height: heightPx } });
    let svg = "";
    stats.labels = [];
    spots.forEach((r, k) => {
      const node = nodes[k];
      if (!r) {
        node.style.visibility = "hidden";
        return;
      }
      node.style.visibility = "visible";
      node.style.transform = `translate(${r.x.toFixed(1)}px, ${r.y.toFixed(1)}px)`;
      stats.labels.push({ text: node.textContent, x: r.x, y: r.y, w: r.w, h: r.h, ax: items[k].x, ay: items[k].y });
      if (r.leader) {
        const cx = Math.min(Math.max(items[k].x, r.x), r.x + r.w);
        const cy = Math.min(Math.max(items[k].y, r.y), r.y + r.h);
        svg += `<line x1="${items[k].x.toFixed(1)}" y1="${items[k].y.toFixed(1)}" x2="${cx.toFixed(1)}" y2="${cy.toFixed(1)}" stroke="#888" stroke-width="1"/>`;
      }
    });
    leaders.innerHTML = svg;
  }

  function draw() {
    pending = false;
    const width = box.clientWidth;
    const heightPx = box.clientHeight;
    if (width === 0 || heightPx === 0) return;
    const size = renderer.getSize(new Vector3());
    if (size.x !== width || size.y !== heightPx) {
      renderer.setSize(width, heightPx);
      camera.aspect = width / heightPx;
      camera.updateProjectionMatrix();
    }
    renderer.render(scene, camera);
    placeAllLabels(width, heightPx);
    const now = performance.now();
    const eye = camera.position.clone().sub(controls.target).normalize();
    stats.eye = [eye.x, eye.y, eye.z]; // the direction the view looks from (a user's turn changes it)
    stats.renders += 1;
    stats.lastRender = now;
    if (poseDirty) {
      poseDirty = false;
      stats.origins = triads.map((g) => [g.matrix.elements[12], g.matrix.elements[13], g.matrix.elements[14]]);
      stats.poseRenders += 1;
      stats.lastPoseRender = now;
      stats.poseSeq = pose.seq ?? -1;
      box.dataset.poseRenders = String(stats.poseRenders);
    }
  }

  function requestDraw() {
    if (!pending) {
      pending = true;
      requestAnimationFrame(draw);
    }
  }

  // camera: an orbit around the view's centre, as matplotlib's default view (azim -60, elev 25)
  const controls = new OrbitControls(camera, renderer.domElement);
  function homeView() {
    const aspect = Math.max(box.clientWidth, 1) / Math.max(box.clientHeight, 1);
    const dist = fitDistance(home.radius, FOV, aspect);
    camera.position.set(...orbitPosition(home.center, dist, sceneSpec.view.azim, sceneSpec.view.elev));
    controls.target.set(...home.center);
    camera.zoom = 1;
    camera.updateProjectionMatrix();
    controls.update();
  }
  controls.addEventListener("change", requestDraw);

  // the keyboard: arrows turn the view about its centre (TURN degrees), + and - zoom, 0 (or Home) resets;
  // JupyterLab's command-mode shortcuts do not see these keys (data-lm-suppress-shortcuts, stopPropagation)
  function viewAngles() {
    const o = camera.position.clone().sub(controls.target);
    const r = o.length() || 1;
    return { r, azim: (Math.atan2(o.y, o.x) * 180) / Math.PI, elev: (Math.asin(Math.max(-1, Math.min(1, o.z / r))) * 180) / Math.PI };
  }
  function turnView(dAzim, dElev, scale) {
    const a = viewAngles();
    const elev = Math.max(-85, Math.min(85, a.elev + dElev));
    camera.position.set(...orbitPosition(controls.target.toArray(), a.r * scale, a.azim + dAzim, elev));
    camera.updateProjectionMatrix();
    controls.update();
    announce();
  }
  canvas.addEventListener("keydown", (e) => {
    const moves = { ArrowLeft: [-TURN, 0, 1], ArrowRight: [TURN, 0, 1], ArrowUp: [0, TURN, 1], ArrowDown: [0, -TURN, 1],
      "+": [0, 0, 1 / 1.2], "=": [0, 0, 1 / 1.2], "-": [0, 0, 1.2], PageUp: [0, 0, 1 / 1.2], PageDown: [0, 0, 1.2] };
    if (e.altKey || e.ctrlKey || e.metaKey) return;
    if (e.key in moves) {
      turnView(...moves[e.key]);
    } else if (e.key === "0" || e.key === "Home") {
      reset.click();
      announce();
    } else {
      return;
    }
    e.preventDefault();
    e.stopPropagation();
    stats.keyTurns += 1;
  });

  // a polite live region: the tool's position and the view, said once things settle (not on every frame)
  const status = document.createElement("div");
  status.className = "puma-status";
  status.setAttribute("role", "status");
  status.setAttribute("aria-live", "polite");
  box.appendChild(status);
  let announceTimer = null;
  function describe() {
    const k = styles.length - 1;
    const f = frameAt(pose.frames, k);
    const p = [f[3], f[7], f[11]].map((x) => Number.parseFloat((x + 0).toPrecision(4)).toString());
    const a = viewAngles();
    const name = styles[k].label ? `frame ${styles[k].label}` : "the tool";
    return `${name} at x ${p[0]}, y ${p[1]}, z ${p[2]}${sceneSpec.units ? ` ${sceneSpec.units}` : ""}; ` +
      `view from azimuth ${Math.round(a.azim)}°, elevation ${Math.round(a.elev)}°`;
  }
  function announce() {
    if (announceTimer !== null) clearTimeout(announceTimer);
    announceTimer = setTimeout(() => {
      announceTimer = null;
      status.textContent = describe();
      stats.status = status.textContent;
    }, 400);
  }

  // ipywidgets' sliders name no handle: give each handle of the panel this viewer sits in its visible label
  function nameSliders() {
    const root = el.closest(".jp-OutputArea-output, .output_subarea, .widget-hbox") || el.parentElement;
    if (!root) return;
    for (const s of root.querySelectorAll(".widget-slider")) {
      const label = s.querySelector(".widget-label");
      const handle = s.querySelector("[role=slider]");
      const text = label ? label.textContent.trim() : "";
      if (handle && text && handle.getAttribute("aria-label") !== text) handle.setAttribute("aria-label", text);
    }
    // the panel's drop-downs (the IK selector) keep their arrow keys: JupyterLab's command-mode shortcuts skip them
    for (const select of root.querySelectorAll("select:not([data-lm-suppress-shortcuts])")) {
      select.setAttribute("data-lm-suppress-shortcuts", "true");
    }
  }
  const sliderWatch = new MutationObserver(nameSliders);
  requestAnimationFrame(() => {
    const root = el.closest(".jp-OutputArea-output, .output_subarea, .widget-hbox") || el.parentElement;
    if (root) sliderWatch.observe(root, { childList: true, subtree: true });
    nameSliders();
  });

  // the points the view must hold for the pose shown: the links, the frames' origins (and the base)
  function posePoints(withBase) {
    const pts = withBase ? [[0, 0, 0]] : [];
    for (let k = 0; k < sceneSpec.points; k += 1) pts.push(pointAt(pose.points, k));
    styles.forEach((_, k) => {
      const f = frameAt(pose.frames, k);
      pts.push([f[3], f[7], f[11]]);
    });
    return pts;
  }
  function poseSphere(withBase) {
    const sphere = boundingSphere(posePoints(withBase), Math.max(...styles.map((st) => st.length)));
    return { center: sphere.center, radius: Math.max(sphere.radius, 0.5 * sceneSpec.radius) };
  }

  // a pose that leaves the picture (a large move) is framed again, seen from where the user turned the view
  function keepInView() {
    if (!started || animView) return;
    camera.updateMatrixWorld();
    const v = new Vector3();
    const ndc = posePoints(false).map((p) => v.set(p[0], p[1], p[2]).project(camera).toArray());
    if (allInView(ndc)) return;
    const aspect = Math.max(box.clientWidth, 1) / Math.max(box.clientHeight, 1);
    const next = reframe(camera.position.toArray(), controls.target.toArray(), poseSphere(false), FOV, aspect);
    camera.position.set(...next.position);
    controls.target.set(...next.target);
    camera.zoom = 1;
    camera.updateProjectionMatrix();
    controls.update();
    stats.reframes += 1;
  }

  // toolbar: reset view
  const bar = document.createElement("div");
  bar.className = "puma-bar";
  const reset = document.createElement("button");
  reset.textContent = "reset view";
  reset.title = "back to the starting view (drag: turn, wheel: zoom, right-drag or shift-drag: pan)";
  reset.addEventListener("click", () => {
    if (!animView) home = poseSphere(true);
    homeView();
    requestDraw();
  });
  bar.appendChild(reset);
  box.appendChild(bar);

  function buildGhosts() {
    disposeChildren(ghostGroup);
    const g = model.get("ghosts") || {};
    const arms = g.arms || [];
    ghostArms = arms.map((arm, k) => {
      const selected = k === g.selected;
      const l = new Links(sceneSpec.points, 0.7 * sceneSpec.link.radius, selected ? 0x1f77b4 : 0x7f7f7f, selected ? 0.55 : 0.22);
      l.update(arm.points);
      const t = makeTriad(styles[styles.length - 1].length * 0.8, { opacity: selected ? 0.8 : 0.3 });
      setMatrix(t, frameAt(arm.frames, styles.length - 1));
      ghostGroup.add(l.group, t);
      return l;
    });
    stats.ghosts = ghostArms.length;
    stats.selected = arms.length ? g.selected : -1;
    requestDraw();
  }

  function buildTargets() {
    disposeChildren(targetGroup);
    targetLabels.forEach(({ node }) => node.remove());
    targetLabels = [];
    const targets = model.get("targets") || [];
    const L = styles[styles.length - 1].length * 1.3;
    for (const t of targets) {
      const triad = makeTriad(L, { opacity: 0.55, shaft: 0.05 });
      setMatrix(triad, t.frame);
      targetGroup.add(triad);
      if (t.label) {
        const node = document.createElement("div");
        node.className = "puma-label target";
        node.textContent = t.label;
        labelLayer.appendChild(node);
        targetLabels.push({ node, xyz: [t.frame[3], t.frame[7], t.frame[11]] });
      }
    }
    requestDraw();
  }

  // animation: precomputed poses played here, with no round trip to the kernel
  let player = null;
  let timer = null;
  function stop() {
    if (timer !== null) clearInterval(timer);
    timer = null;
    if (player) player.play.textContent = "▶ play";
  }
  function showStep(k) {
    const anim = model.get("animation");
    const poses = anim.poses || [];
    if (!poses.length) return;
    const i = Math.min(Math.max(k, 0), poses.length - 1);
    player.range.value = String(i);
    player.count.textContent = `${i + 1} / ${poses.length}`;
    stats.animStep = i;
    stats.animSteps = poses.length;
    applyPose({ ...poses[i], seq: pose.seq });
    requestDraw();
  }
  function buildPlayer() {
    stop();
    if (player) player.node.remove();
    player = null;
    const anim = model.get("animation") || {};
    const poses = anim.poses || [];
    animView = anim.view || null;
    const view = animView || { center: sceneSpec.center, radius: sceneSpec.radius };
    if (view.center !== home.center || view.radius !== home.radius) {
      home = view;
      if (started) homeView();
    }
    if (!poses.length) {
      applyPose(model.get("pose"));
      requestDraw();
      return;
    }
    const node = document.createElement("span");
    node.className = "puma-player";
    const play = document.createElement("button");
    play.textContent = "▶ play";
    const range = document.createElement("input");
    range.type = "range";
    range.min = "0";
    range.max = String(poses.length - 1);
    range.step = "1";
    range.value = "0";
    range.setAttribute("aria-label", "animation step");
    range.setAttribute("data-lm-suppress-shortcuts", "true"); // the arrow keys step it, not JupyterLab's shortcuts
    const count = document.createElement("span");
    node.append(play, range, count);
    bar.prepend(node);
    player = { node, play, range, count };
    range.addEventListener("input", () => {
      stop();
      showStep(Number(range.value));
    });
    play.addEventListener("click", () => {
      if (timer !== null) {
        stop();
        return;
      }
      let i = Number(range.value);
      if (i >= poses.length - 1) i = -1;
      play.textContent = "❚❚ pause";
      timer = setInterval(() => {
        i += 1;
        if (i >= poses.length) {
          if (anim.loop) i = 0;
          else {
            stop();
            return;
          }
        }
        showStep(i);
      }, 1000 / (anim.fps || 12));
    });
    showStep(0);
  }

  const onPose = () => {
    stats.lastPoseMessage = performance.now();
    stop();
    applyPose(model.get("pose"));
    keepInView();
    requestDraw();
    announce();
  };
  model.on("change:pose", onPose);
  model.on("change:ghosts", buildGhosts);
  model.on("change:targets", buildTargets);
  model.on("change:animation", buildPlayer);

  applyPose(pose);
  buildGhosts();
  buildTargets();
  buildPlayer();
  const resize = new ResizeObserver(() => requestDraw());
  resize.observe(box);
  // the first view is set once the box has its size on the page
  requestAnimationFrame(() => {
    started = true;
    homeView();
    controls.saveState();
    requestDraw();
    announce();
  });

  return () => {
    stop();
    resize.disconnect();
    sliderWatch.disconnect();
    if (announceTimer !== null) clearTimeout(announceTimer);
    model.off("change:pose", onPose);
    model.off("change:ghosts", buildGhosts);
    model.off("change:targets", buildTargets);
    model.off("change:animation", buildPlayer);
    controls.dispose();
    disposeChildren(scene);
    renderer.dispose();
    renderer.forceContextLoss();
    ghostArms = [];
  };
}

export default { render };

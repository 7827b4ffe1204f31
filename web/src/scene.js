// The page's 3D view: UGVs with their decks, UAVs and their reference paths on a grid, in
// the world frame or a chosen UGV's frame G_k (x forward, z up).
// With a simulator on the station's host the station sends its world poses ("world"): every
// vehicle is placed in the world, and a UGV's frame is the world seen from that UGV. A real
// fleet has no world truth: the UGV frames only, each UAV where its relative state puts it.
import * as THREE from "three";

const kBackground = 0x0d1117;
const kDeckColor = 0x2e7d32;
const kFrameDeckColor = 0x66bb6a;  // the deck of the UGV whose frame is shown
const kUavColor = 0xffa726;
const kPathColor = 0x58a6ff;
const kGridSizeM = 60;            // 1 m cells, under the view's target; its far part fogged
const kCameraOffset = new THREE.Vector3(-4, -5, 3.5);
// Drawn when the state changes, not every animation frame, and at most 5 times a second:
// software WebGL (SwiftShader, no GPU) takes ~0.1 s a frame, and the page must leave the
// ground station's computer to the fleet.
const kDrawPeriodMs = 200;

// The pose of UGV k in the world (its frame G_k): translation, then yaw about z.
function ugvMatrix(ugv) {
  const [x, y, z] = ugv.position_m;
  return new THREE.Matrix4().makeRotationZ(ugv.yaw_rad).setPosition(x, y, z);
}

// A square grid of 1 m cells in the xy plane, drawn as 2 m pieces: SwiftShader (software
// WebGL, no GPU) drops whole lines that reach far behind the camera (THREE.GridHelper's lines
// span the grid), which left a grid of 40 m or more with no lines near the camera.
function makeGrid(sizeM) {
  const h = sizeM / 2;
  const piece = 2;
  const p = [];
  for (let k = -h; k <= h; k += 1) {
    for (let a = -h; a < h; a += piece) p.push(a, k, 0, a + piece, k, 0, k, a, 0, k, a + piece, 0);
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.Float32BufferAttribute(p, 3));
  return new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0x3a4654 }));
}

// `stats.view` (the browser tests read it): the frame of the last picture drawn and how
// many were drawn.
export function createScene(canvas, select, stats = {}) {
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(kBackground);
  // The grid fades out past the vehicles (its far edge would draw a band along the horizon).
  scene.fog = new THREE.Fog(kBackground, 10, 25);
  const camera = new THREE.PerspectiveCamera(50, canvas.width / canvas.height, 0.05, 400);
  camera.up.set(0, 0, 1);
  const grid = makeGrid(kGridSizeM);
  const sun = new THREE.DirectionalLight(0xffffff, 0.9);
  sun.position.set(3, -2, 6);
  // `root` holds the vehicles in world coordinates (or G_k's without a world); its matrix
  // takes them into the shown frame.
  const root = new THREE.Group();
  root.matrixAutoUpdate = false;
  scene.add(grid, new THREE.AxesHelper(1), new THREE.AmbientLight(0xffffff, 0.6), sun, root);

  const decks = {};
  const uavs = {};
  const paths = {};
  let frame = "world";  // the operator's choice
  let shown = "world";  // what is drawn: the choice, or the first frame offered while it is not
  let last = null;

  function deck(k) {
    if (!decks[k]) {
      decks[k] = new THREE.Mesh(new THREE.BoxGeometry(1.0, 0.8, 0.1),
        new THREE.MeshLambertMaterial({ color: kDeckColor }));
      decks[k].matrixAutoUpdate = false;
      root.add(decks[k]);
    }
    return decks[k];
  }
  function uav(u) {
    if (!uavs[u]) {
      uavs[u] = new THREE.Mesh(new THREE.SphereGeometry(0.15, 16, 12),
        new THREE.MeshLambertMaterial({ color: kUavColor }));
      root.add(uavs[u]);
    }
    return uavs[u];
  }
  function setPath(u, points, matrix) {
    if (paths[u]) { root.remove(paths[u]); paths[u].geometry.dispose(); delete paths[u]; }
    if (!points) return;
    const g = new THREE.BufferGeometry().setFromPoints(
      points.map((q) => new THREE.Vector3(q[0], q[1], q[2]).applyMatrix4(matrix)));
    paths[u] = new THREE.Line(g, new THREE.LineBasicMaterial({ color: kPathColor }));
    root.add(paths[u]);
  }
  // The deck's top is G_k's z = 0, where a UAV lands.
  function placeDeck(k, matrix) {
    const d = deck(k);
    d.matrix.copy(matrix).multiply(new THREE.Matrix4().makeTranslation(0, 0, -0.05));
    d.material.color.setHex(shown === `ugv:${k}` ? kFrameDeckColor : kDeckColor);
    d.visible = true;
  }

  // Everything in world coordinates; the shown frame is the world or G_k.
  function placeInWorld(live, world) {
    const poses = world.ugvs.map(ugvMatrix);
    poses.forEach((m, k) => placeDeck(k, m));
    world.uavs.forEach((s, u) => uav(u).position.set(...s.position_m));
    for (const u in uavs) uavs[u].visible = u < world.uavs.length;
    for (const [u, l] of Object.entries(live ?? {})) {
      const ref = l.reference;
      setPath(u, ref && poses[ref.ugv] ? ref.points : null, poses[ref?.ugv] ?? new THREE.Matrix4());
    }
    const k = shown.startsWith("ugv:") ? Number(shown.slice(4)) : -1;
    if (poses[k]) {
      root.matrix.copy(poses[k]).invert();
      return { target: new THREE.Vector3(0, 0, 0.5), distance: 1 };
    }
    root.matrix.identity();
    // The world seen from above the fleet's middle, far enough back to hold every vehicle.
    const box = new THREE.Box3();
    for (const m of poses) box.expandByPoint(new THREE.Vector3().setFromMatrixPosition(m));
    for (const s of world.uavs) box.expandByPoint(new THREE.Vector3(...s.position_m));
    const target = box.isEmpty() ? new THREE.Vector3() : box.getCenter(new THREE.Vector3());
    // Whole metres: the camera steps with the fleet a grid cell at a time, so the grid stands
    // still on the screen and only the vehicles move (a frame redrawn 5 times a second).
    target.set(Math.round(target.x), Math.round(target.y), 0.5);
    const extent = box.isEmpty() ? 0 : box.getSize(new THREE.Vector3()).length();
    // Stepped too (halves of the camera offset): a picture changes when the fleet does.
    return { target, distance: Math.max(1, Math.ceil(extent / 3) / 2) };
  }

  // No world: G_k's own view, its deck at the origin and each UAV by its relative state.
  function placeInUgvFrame(live) {
    root.matrix.identity();
    const k = Number(shown.slice(4));
    for (const j in decks) decks[j].visible = false;
    placeDeck(k, new THREE.Matrix4());
    for (const [u, l] of Object.entries(live ?? {})) {
      const p = l.relative?.[String(k)];
      uav(u).visible = !!p;
      if (p) uavs[u].position.set(p[0], p[1], p[2]);
      setPath(u, l.reference && l.reference.ugv === k ? l.reference.points : null, new THREE.Matrix4());
    }
    return { target: new THREE.Vector3(0, 0, 0.5), distance: 1 };
  }

  function offerFrames(ugvIds, hasWorld) {
    const values = [...(hasWorld ? ["world"] : []), ...ugvIds.map((k) => `ugv:${k}`)];
    if ([...select.options].map((o) => o.value).join() !== values.join()) {
      select.innerHTML = values.map((v) =>
        `<option value="${v}">${v === "world" ? "world frame" : `frame of UGV ${v.slice(4)}`}</option>`).join("");
    }
    shown = values.includes(frame) || !values.length ? frame : values[0];
    select.value = shown;
  }

  function place() {
    if (!last) return;
    const { live, fleet, world } = last;
    const ugvIds = world ? world.ugvs.map((_, k) => k)
      : fleet.filter((r) => r.kind === "ugv-agent" && r.id !== null).map((r) => r.id);
    offerFrames(ugvIds, !!world);
    if (!world && !shown.startsWith("ugv:")) return;
    const view = world ? placeInWorld(live, world) : placeInUgvFrame(live);
    root.matrixWorldNeedsUpdate = true;
    // Moved by whole 10 m: its 1 m lines stay where they are in the shown frame.
    grid.position.set(10 * Math.round(view.target.x / 10), 10 * Math.round(view.target.y / 10), 0);
    camera.position.copy(view.target).addScaledVector(kCameraOffset, view.distance);
    scene.fog.near = 1.5 * kCameraOffset.length() * view.distance;
    scene.fog.far = scene.fog.near + 25;
    camera.lookAt(view.target);
  }

  // Drawn in the page's own frames (main.js calls update from its animation frame): now when
  // the last picture is kDrawPeriodMs old, else by a later update; the last state before the
  // updates stop is drawn by a timer.
  let lastDrawMs = -Infinity;
  let trailing = 0;
  function render() {
    clearTimeout(trailing);
    trailing = 0;
    lastDrawMs = performance.now();
    place();
    renderer.render(scene, camera);
    stats.view = { frame: shown, draws: (stats.view?.draws ?? 0) + 1 };
  }
  function draw() {
    if (performance.now() - lastDrawMs >= kDrawPeriodMs) {
      render();
      return;
    }
    clearTimeout(trailing);
    trailing = setTimeout(() => requestAnimationFrame(render), 2 * kDrawPeriodMs);
  }

  select.onchange = (e) => { frame = e.target.value; requestAnimationFrame(render); };
  camera.position.copy(kCameraOffset);
  camera.lookAt(0, 0, 0.5);
  draw();
  return {
    update(live, fleet, world) {
      last = { live, fleet, world };
      draw();
    },
    frame: () => frame,
  };
}

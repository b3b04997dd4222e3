// rad serve's page: the solve in 3D (three.js), its progress and hierarchy, and the edits
// (lil-gui) that the server applies between shots without starting over.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import GUI from 'lil-gui';

const $ = (id) => document.getElementById(id);
const MESH_MAGIC = 0x4d444152;   // "RADM": header, positions, colours, indices, face polygons
const COLOUR_MAGIC = 0x43444152; // "RADC": header, colours

// ---------------------------------------------------------------- state

let scene = null;           // /api/scene
let status = null;          // the latest snapshot status (server-sent events)
let polygonObject = null;   // Int32Array: polygon -> Pure
let facePolygon = null;     // Int32Array: face -> polygon (of the geometry shown)
let meshVersion = 0, colourVersion = 0;
const latest = { version: 0, mesh_version: 0 };
let selected = -1;          // selected object id
let lastEditTime = 0;       // ms; panel values are not overwritten right after the user's edits
let lightEditTime = -Infinity;  // the same for the lights (none yet: the first status fills them)
const settings = { onClick: 'select', wireframe: false, exposure: 0 };

// ---------------------------------------------------------------- 3D view

const canvas = $('canvas');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(0x15171a);
const world = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(39.3, 1, 1, 1e5);
const controls = new OrbitControls(camera, canvas);
controls.addEventListener('change', () => (dirty = true));

const geometry = new THREE.BufferGeometry();
// Colours are tone-mapped linear values from the server; three.js encodes them as sRGB on
// output, as rad's PNG writer does. Faces are one-sided, as in rad's images.
const surface = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({
  vertexColors: true, side: THREE.FrontSide,
  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
}));
const wire = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({
  color: 0x000000, wireframe: true, transparent: true, opacity: 0.25,
}));
wire.visible = false;
const highlight = new THREE.LineSegments(new THREE.BufferGeometry(),
  new THREE.LineBasicMaterial({ color: 0xf0c040, transparent: true, opacity: 0.35 }));
world.add(surface, wire, highlight);
let dirty = true;

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (w === 0 || h === 0) return;
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  dirty = true;
}
new ResizeObserver(resize).observe(canvas);

function frame() {
  controls.update();
  if (dirty) {
    renderer.render(world, camera);
    dirty = false;
  }
  requestAnimationFrame(frame);
}

function applyMesh(buffer) {
  const h = new Uint32Array(buffer, 0, 8);
  if (h[0] !== MESH_MAGIC) throw new Error('not a mesh buffer');
  const n = h[3], ni = h[4];
  let at = 32;
  const positions = new Float32Array(buffer, at, 3 * n); at += 12 * n;
  const colours = new Float32Array(buffer, at, 3 * n); at += 12 * n;
  const indices = new Uint32Array(buffer, at, ni); at += 4 * ni;
  facePolygon = new Int32Array(buffer, at, ni / 3);
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  geometry.setIndex(new THREE.BufferAttribute(indices, 1));
  geometry.computeBoundingSphere();
  meshVersion = h[2];
  colourVersion = h[1];
  updateHighlight();
  dirty = true;
}

function applyColours(buffer) {
  const h = new Uint32Array(buffer, 0, 8);
  if (h[0] !== COLOUR_MAGIC) throw new Error('not a colour buffer');
  const attr = geometry.getAttribute('color');
  if (h[2] !== meshVersion || !attr || attr.count !== h[3]) return false;  // the mesh changed
  attr.array.set(new Float32Array(buffer, 32, 3 * h[3]));
  attr.needsUpdate = true;
  colourVersion = h[1];
  dirty = true;
  return true;
}

// Fetches what the latest snapshot changed: the whole mesh when its geometry changed, else only
// the colours. One fetch at a time; snapshots that arrive meanwhile are folded into the next.
let syncing = false;
async function sync() {
  if (syncing) return;
  syncing = true;
  try {
    while (meshVersion < latest.mesh_version || colourVersion < latest.version) {
      const wantMesh = meshVersion < latest.mesh_version;
      const r = await fetch(wantMesh ? '/api/mesh' : '/api/colours', { cache: 'no-store' });
      if (!r.ok) throw new Error(`${r.status} ${r.statusText}`);
      const buffer = await r.arrayBuffer();
      const h = new Uint32Array(buffer, 0, 8);
      latest.version = Math.max(latest.version, h[1]);
      latest.mesh_version = Math.max(latest.mesh_version, h[2]);
      if (wantMesh) applyMesh(buffer);
      else applyColours(buffer);
      if (!window.rad.ready && meshVersion > 0) window.rad.ready = true;
    }
  } catch (e) {
    notice(`could not fetch the mesh: ${e.message}`);
    setTimeout(sync, 1000);
  } finally {
    syncing = false;
  }
}

// The selected object's faces, outlined.
function updateHighlight() {
  highlight.geometry.dispose();
  highlight.geometry = new THREE.BufferGeometry();
  const index = geometry.getIndex();
  if (selected < 0 || !index || !facePolygon) { dirty = true; return; }
  const o = scene.objects[selected];
  const lo = o.first_triangle, hi = o.first_triangle + o.triangle_count;
  const pos = geometry.getAttribute('position').array, idx = index.array;
  const lines = [];
  for (let f = 0; f < facePolygon.length; ++f) {
    const p = facePolygon[f];
    if (p < lo || p >= hi) continue;
    for (let e = 0; e < 3; ++e) {
      const a = idx[3 * f + e], b = idx[3 * f + (e + 1) % 3];
      lines.push(pos[3 * a], pos[3 * a + 1], pos[3 * a + 2], pos[3 * b], pos[3 * b + 1], pos[3 * b + 2]);
    }
  }
  highlight.geometry.setAttribute('position', new THREE.Float32BufferAttribute(lines, 3));
  dirty = true;
}

// ---------------------------------------------------------------- picking

const raycaster = new THREE.Raycaster();
let down = null;
canvas.addEventListener('pointerdown', (e) => (down = { x: e.clientX, y: e.clientY, t: performance.now() }));
canvas.addEventListener('pointerup', (e) => {
  if (!down || e.button !== 0) return;
  const moved = Math.hypot(e.clientX - down.x, e.clientY - down.y);
  const quick = performance.now() - down.t < 500;
  down = null;
  if (moved > 4 || !quick) return;  // an orbit, not a click
  const polygon = pick(e.clientX, e.clientY);
  if (polygon < 0) return;
  if (e.shiftKey || settings.onClick === 'subdivide') subdivide(polygon);
  else select(polygonObject[polygon]);
});

function pick(clientX, clientY) {
  if (!facePolygon) return -1;
  const r = canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  // Faces are drawn one-sided: pick only the ones facing the camera.
  const hit = raycaster.intersectObject(surface, false).find((h) => h.face.normal.dot(raycaster.ray.direction) < 0);
  return hit ? facePolygon[hit.faceIndex] : -1;
}

// ---------------------------------------------------------------- requests

async function post(path, body = {}) {
  const r = await fetch(path, {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body),
  });
  if (!r.ok) {
    const j = await r.json().catch(() => ({ error: r.statusText }));
    notice(`${path}: ${j.error}`);
  }
  return r.ok;
}

function subdivide(polygon) {
  post('/api/subdivide', { polygon });
  if (polygonObject[polygon] !== selected) select(polygonObject[polygon]);
}

// Material edits while a slider moves: at most one request per 100 ms, the last value always
// sent (the server also keeps only the newest pending edit of an object).
let pendingEdit = null, editTimer = null;
function editMaterial(object, patch) {
  lastEditTime = performance.now();
  pendingEdit = pendingEdit && pendingEdit.object === object ? { ...pendingEdit, ...patch } : { object, ...patch };
  if (!editTimer) {
    editTimer = setTimeout(() => {
      editTimer = null;
      const e = pendingEdit;
      pendingEdit = null;
      if (e) post('/api/material', e);
    }, 100);
  }
}

// Light edits the same way, per light.
const pendingLights = new Map(), lightTimers = new Map();
function editLight(light, patch) {
  lightEditTime = performance.now();
  pendingLights.set(light, { ...(pendingLights.get(light) || {}), ...patch });
  if (!lightTimers.has(light)) {
    lightTimers.set(light, setTimeout(() => {
      lightTimers.delete(light);
      const e = pendingLights.get(light);
      pendingLights.delete(light);
      if (e) post('/api/light', { light, ...e });
    }, 100));
  }
}

// ---------------------------------------------------------------- panel

function notice(text) { $('notice').textContent = text; }

const gui = new GUI({ container: $('controls'), title: 'Selection', width: 300 });
const material = { colour: [1, 1, 1], reflectivity: 0, emission: 0 };
const info = { object: '(click an object)', kind: '', elements: 0 };
gui.add(info, 'object').name('object').disable();
const elementsCtl = gui.add(info, 'elements').name('elements').disable();
const colourCtl = gui.addColor(material, 'colour').name('colour')
  .onChange((v) => editMaterial(selected, { colour: [...v] }));
const reflectivityCtl = gui.add(material, 'reflectivity', 0, 1, 0.01).name('reflectivity')
  .onChange((v) => editMaterial(selected, { reflectivity: v }));
const emissionCtl = gui.add(material, 'emission', 0, 100, 0.01).name('emission (light)')
  .onChange((v) => editMaterial(selected, { emission: v }));
for (const [c, id] of [[colourCtl, 'colour'], [reflectivityCtl, 'reflectivity'], [emissionCtl, 'emission']]) {
  c.domElement.dataset.control = id;
}
const viewGui = gui.addFolder('View');
viewGui.add(settings, 'onClick', { 'select object': 'select', 'subdivide polygon': 'subdivide' })
  .name('click in 3D').domElement.dataset.control = 'click-mode';
viewGui.add(settings, 'wireframe').name('show elements').onChange((v) => { wire.visible = v; dirty = true; });
viewGui.add(settings, 'exposure', -6, 6, 0.1).name('exposure (stops)')
  .onFinishChange((v) => post('/api/exposure', { stops: v }));
viewGui.add({ refit: () => post('/api/exposure', { refit: true }) }, 'refit').name('refit exposure');
viewGui.add({ frame: () => frameCamera() }, 'frame').name('reset view');
showControls();

function showControls() {
  const o = selected >= 0 ? scene.objects[selected] : null;
  const pure = o && o.kind === 'Pure';
  for (const c of [colourCtl, reflectivityCtl, emissionCtl]) c.show(pure);
  info.object = o ? `${o.name} (${o.kind})` : '(click an object)';
  refreshControls(true);
}

function refreshControls(force) {
  if (selected < 0 || !status) return;
  const s = status.objects[selected];
  info.elements = s.elements;
  elementsCtl.updateDisplay();
  gui.controllersRecursive()[0].updateDisplay();
  if (!('emission' in s)) return;
  if (!force && performance.now() - lastEditTime < 1500) return;  // the user is editing
  material.colour = [...s.colour];
  material.reflectivity = s.reflectivity;
  material.emission = s.emission;
  emissionCtl.max(Math.max(4 * scene.max_emission, 2 * s.emission, 1));
  for (const c of [colourCtl, reflectivityCtl, emissionCtl]) c.updateDisplay();
}

// The scene's lights: colour, intensity in its unit (cd or lx) and a switch. Off is intensity 0;
// on again restores the intensity it had (a light the scene leaves off is turned on by giving it
// an intensity).
const lightControls = [];
function buildLights() {
  if (!scene.lights || scene.lights.length === 0) return;
  $('lights-section').hidden = false;
  const lightsGui = new GUI({ container: $('lights'), title: 'Lights', width: 300 });
  for (const l of scene.lights) {
    const folder = lightsGui.addFolder(`${l.name || `light ${l.id}`} (${l.kind})`);
    const state = { colour: [1, 1, 1], intensity: 0, on: true, lit: 0 };
    const colour = folder.addColor(state, 'colour').name('colour')
      .onChange((v) => editLight(l.id, { colour: [...v] }));
    const intensity = folder.add(state, 'intensity').min(0).name(`intensity (${l.unit})`)
      .onChange((v) => {
        if (v > 0) state.lit = v;
        state.on = v > 0;
        on.updateDisplay();
        editLight(l.id, { intensity: v });
      });
    const on = folder.add(state, 'on').name('on').onChange((v) => {
      state.intensity = v ? state.lit : 0;
      intensity.updateDisplay();
      editLight(l.id, { intensity: state.intensity });
    });
    colour.domElement.dataset.control = `light-${l.id}-colour`;
    intensity.domElement.dataset.control = `light-${l.id}-intensity`;
    on.domElement.dataset.control = `light-${l.id}-on`;
    lightControls.push({ state, colour, intensity, on });
  }
}

// Light groups: a dimmer per group mixes the groups' solutions into the colours shown, with no
// new solve (every group's light, every bounce, is solved apart).
let dimmerEditTime = -Infinity, dimmerTimer = null;
const dimmers = [], dimmerControls = [];
function buildGroups() {
  if (!scene.light_groups || scene.light_groups.length === 0) return;
  $('groups-section').hidden = false;
  const groupsGui = new GUI({ container: $('groups'), title: 'Light groups', width: 300 });
  scene.light_groups.forEach((name, g) => {
    dimmers.push({ dimmer: 1 });
    const c = groupsGui.add(dimmers[g], 'dimmer', 0, 4, 0.01).name(name || '(no group)')
      .onChange(() => {
        dimmerEditTime = performance.now();
        if (!dimmerTimer) {
          dimmerTimer = setTimeout(() => {
            dimmerTimer = null;
            post('/api/dimmers', { dimmers: dimmers.map((d) => d.dimmer) });
          }, 100);
        }
      });
    c.domElement.dataset.control = `group-${g}-dimmer`;
    dimmerControls.push(c);
  });
}

function refreshGroups() {
  if (!status || !status.dimmers || performance.now() - dimmerEditTime < 1500) return;
  status.dimmers.forEach((d, g) => {
    if (!dimmerControls[g]) return;
    dimmers[g].dimmer = d;
    dimmerControls[g].updateDisplay();
  });
}

function refreshLights() {
  if (!status || !status.lights || performance.now() - lightEditTime < 1500) return;
  status.lights.forEach((s, i) => {
    const c = lightControls[i];
    if (!c) return;
    c.state.colour = [...s.colour];
    c.state.intensity = s.intensity;
    c.state.on = s.intensity > 0;
    if (s.intensity > 0 || c.state.lit === 0) c.state.lit = s.intensity;
    for (const k of [c.colour, c.intensity, c.on]) k.updateDisplay();
  });
}

function select(id) {
  selected = id;
  document.querySelectorAll('.tree .item').forEach((el) => el.classList.toggle('selected', Number(el.dataset.id) === id));
  const item = document.querySelector(`.tree .item[data-id="${id}"]`);
  if (item) item.scrollIntoView({ block: 'nearest' });
  showControls();
  updateHighlight();
}

function buildTree() {
  const kinds = { Assembly: 'A', Composite: 'C', Pure: 'P' };
  const make = (id) => {
    const o = scene.objects[id];
    const li = document.createElement('li');
    const item = document.createElement('div');
    item.className = 'item';
    item.dataset.id = id;
    item.title = `${o.kind}: ${o.triangle_count} triangles`;
    item.innerHTML = '<span class="kind"></span><span class="name"></span><span class="count"></span>';
    item.querySelector('.kind').textContent = kinds[o.kind];
    item.querySelector('.name').textContent = o.name;
    item.addEventListener('click', () => select(id));
    li.appendChild(item);
    if (o.children.length) {
      const ul = document.createElement('ul');
      for (const c of o.children) ul.appendChild(make(c));
      li.appendChild(ul);
    }
    return li;
  };
  for (const r of scene.roots) $('tree').appendChild(make(r));
}

function drawChart() {
  const c = $('chart'), g = c.getContext('2d');
  const w = (c.width = c.clientWidth * devicePixelRatio), h = (c.height = c.clientHeight * devicePixelRatio);
  g.clearRect(0, 0, w, h);
  const pts = status.history.filter(([, f]) => f > 0);
  if (pts.length < 1) return;
  const goal = Math.log10(scene.converge);
  const lo = Math.min(goal, ...pts.map(([, f]) => Math.log10(f))) - 0.2, hi = 0.1;
  const maxShot = Math.max(pts[pts.length - 1][0], 1);
  const x = (s) => (s / maxShot) * (w - 4) + 2, y = (l) => ((hi - l) / (hi - lo)) * (h - 4) + 2;
  g.strokeStyle = '#555';
  g.setLineDash([4, 4]);
  g.beginPath(); g.moveTo(0, y(goal)); g.lineTo(w, y(goal)); g.stroke();
  g.setLineDash([]);
  g.strokeStyle = '#f0c040';
  g.lineWidth = 1.5 * devicePixelRatio;
  g.beginPath();
  pts.forEach(([s, f], i) => (i ? g.lineTo(x(s), y(Math.log10(f))) : g.moveTo(x(s), y(Math.log10(f)))));
  g.stroke();
  g.fillStyle = '#9aa0a6';
  g.font = `${10 * devicePixelRatio}px sans-serif`;
  g.fillText('log unshot fraction', 4, 12 * devicePixelRatio);
}

function onStatus(s) {
  status = s;
  window.rad.status = s;
  window.rad.snapshots += 1;
  latest.version = Math.max(latest.version, s.version);
  latest.mesh_version = Math.max(latest.mesh_version, s.mesh_version);
  sync();
  const badge = $('status');
  badge.textContent = s.status;
  badge.className = `badge ${s.status}`;
  $('pause').textContent = s.status === 'paused' ? 'Resume' : 'Pause';
  $('shots').textContent = s.shots.toLocaleString();
  $('unshot').textContent = s.unshot_fraction.toExponential(2);
  $('rays').textContent = s.rays_per_second > 0 ? `${(s.rays_per_second / 1e6).toFixed(2)} M` : '–';
  $('elements').textContent = `${s.elements.toLocaleString()} (${s.vertices.toLocaleString()} vertices)`;
  $('seconds').textContent = `${s.seconds.toFixed(1)} s`;
  if (s.notice) notice(s.notice);
  document.querySelectorAll('.tree .item').forEach((el) => {
    el.querySelector('.count').textContent = s.objects[Number(el.dataset.id)].elements.toLocaleString();
  });
  refreshControls(false);
  refreshLights();
  refreshGroups();
  drawChart();
}

function frameCamera() {
  const c = scene.camera;
  camera.position.set(...c.eye);
  camera.up.set(...c.up);
  camera.fov = c.fov;
  const lo = new THREE.Vector3(...scene.bounds.min), hi = new THREE.Vector3(...scene.bounds.max);
  const size = lo.distanceTo(hi) || 1;
  camera.near = size / 1000;
  camera.far = size * 50;
  camera.updateProjectionMatrix();
  controls.target.set(...c.target);
  controls.update();
  dirty = true;
}

// The current view as rad's --camera argument, so the PNG export matches it.
function cameraArgument() {
  const e = camera.position, t = controls.target, f = (v) => v.toPrecision(7);
  return [e.x, e.y, e.z, t.x, t.y, t.z, camera.fov].map(f).join(',');
}
$('export-png').addEventListener('click', (ev) => {
  const w = Math.min(4096, Math.max(16, Math.round(canvas.clientWidth)));
  const h = Math.min(4096, Math.max(16, Math.round(canvas.clientHeight)));
  ev.currentTarget.href = `/api/export.png?camera=${cameraArgument()}&size=${w}x${h}`;
});
$('pause').addEventListener('click', () => post(status && status.status === 'paused' ? '/api/resume' : '/api/pause'));
$('restart').addEventListener('click', () => post('/api/restart', { materials: 'current' }));
$('reset').addEventListener('click', () => {
  lastEditTime = 0;
  lightEditTime = -Infinity;
  post('/api/restart', { materials: 'original' });
});

// ---------------------------------------------------------------- for tests and the console

window.rad = {
  ready: false,
  snapshots: 0,  // snapshot events received
  get scene() { return scene; },
  status: null,
  get meshVersion() { return meshVersion; },
  get colourVersion() { return colourVersion; },
  objectId(name) { return scene.objects.findIndex((o) => o.name === name); },
  elements(name) { return status.objects[this.objectId(name)].elements; },
  lightId(name) { return scene.lights.findIndex((l) => l.name === name); },
  /// CSS pixel position of a world point, relative to the canvas' top-left corner.
  project(p) {
    const v = new THREE.Vector3(...p).project(camera);
    return [(v.x + 1) / 2 * canvas.clientWidth, (1 - v.y) / 2 * canvas.clientHeight];
  },
  /// Mean sRGB bytes of the (2r+1)² drawn pixels around a world point's projection.
  pixelAt(p, r = 2) {
    const [cx, cy] = this.project(p);
    renderer.render(world, camera);  // read in the same task as the draw
    const gl = renderer.getContext(), dpr = renderer.getPixelRatio();
    const n = 2 * r + 1, px = new Uint8Array(4 * n * n);
    const x = Math.round(cx * dpr) - r, y = Math.round(gl.drawingBufferHeight - cy * dpr) - r;
    gl.readPixels(x, y, n, n, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const sum = [0, 0, 0];
    for (let i = 0; i < n * n; ++i) for (let k = 0; k < 3; ++k) sum[k] += px[4 * i + k];
    return sum.map((s) => s / (n * n));
  },
};

// ---------------------------------------------------------------- start

async function main() {
  const r = await fetch('/api/scene');
  scene = await r.json();
  document.title = `${scene.name} · rad serve`;
  $('scene-name').textContent = scene.name;
  const triangles = scene.objects.reduce((n, o) => (o.kind === 'Pure' ? n + o.triangle_count : n), 0);
  polygonObject = new Int32Array(triangles);
  for (const o of scene.objects) {
    if (o.kind === 'Pure') polygonObject.fill(o.id, o.first_triangle, o.first_triangle + o.triangle_count);
  }
  buildTree();
  buildLights();
  buildGroups();
  resize();
  frameCamera();
  requestAnimationFrame(frame);
  const events = new EventSource('/api/events');
  events.addEventListener('snapshot', (e) => onStatus(JSON.parse(e.data)));
  events.addEventListener('open', () => ($('connection').hidden = true));
  events.addEventListener('error', () => ($('connection').hidden = false));
}
main().catch((e) => notice(`rad serve: ${e.message}`));

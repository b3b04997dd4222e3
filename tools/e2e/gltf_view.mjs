// A textured glTF that rad wrote, shown by three.js's GLTFLoader in headless Chromium (Debian's,
// driven by playwright-core): the texture shows (the checker floor's squares keep their hues) and
// the light shows (the floor under the lamp is brighter than in the corner). Saves a screenshot.
// The scene is tests/export/texture_output_test.cpp's room (TextureOutput.*, written to
// BUILD/test_out/texture_output/room.glb): a closed unit cube, a lamp in the ceiling's middle.
//
//   node gltf_view.mjs --gltf build/test_out/texture_output/room.glb \
//        --modules build/web/node_modules --out build/e2e
//
// Exits 0 on success, 1 on failure, 77 (ctest SKIP_RETURN_CODE) when Chromium or the npm
// modules are missing.
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';

const SKIP = 77;
const CHROMIUM = '/usr/bin/chromium';
const args = Object.fromEntries(
  process.argv.slice(2).reduce((pairs, a, i, all) => (a.startsWith('--') ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
for (const k of ['gltf', 'modules', 'out']) {
  if (!args[k]) { console.error(`missing --${k}`); process.exit(2); }
}
function skip(why) {
  console.log(`SKIP: ${why} (install with: source tools/setup.sh && rad_install_web)`);
  process.exit(SKIP);
}
if (!fs.existsSync(CHROMIUM)) skip(`${CHROMIUM} not found`);
for (const m of ['playwright-core', 'three']) {
  if (!fs.existsSync(path.join(args.modules, m, 'package.json'))) skip(`npm module ${m} not found in ${args.modules}`);
}
if (!fs.existsSync(args.gltf)) { console.error(`FAIL: ${args.gltf} not found`); process.exit(1); }
const { chromium } = createRequire(path.resolve(args.modules, 'noop.js'))('playwright-core');

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}
const fmt = (c) => `(${c.map((x) => x.toFixed(0)).join(', ')})`;
const luminance = ([r, g, b]) => 0.2126 * r + 0.7152 * g + 0.0722 * b;

// The page: the model seen from inside the room, near the ceiling, looking down at the floor.
const page = `<!doctype html><html><body style="margin:0;background:#000">
<canvas id="c" width="800" height="600"></canvas>
<script type="importmap">{"imports": {"three": "/three/build/three.module.js",
  "three/addons/": "/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const canvas = document.getElementById('c');
const renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true });
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(70, 800 / 600, 0.01, 10);
camera.position.set(0.5, 0.9, 0.97);
camera.lookAt(0.5, 0.0, 0.45);
camera.updateMatrixWorld();
new GLTFLoader().load('/model.glb', (gltf) => {
  scene.add(gltf.scene);
  renderer.render(scene, camera);
  const gl = renderer.getContext();
  window.pixelAt = (p) => {
    const v = new THREE.Vector3(...p).project(camera);
    const x = Math.round((v.x + 1) / 2 * 800), y = Math.round((1 - v.y) / 2 * 600);
    const px = new Uint8Array(4);
    gl.readPixels(x, 600 - 1 - y, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return [px[0], px[1], px[2]];
  };
  window.materials = gltf.parser.json.materials.map((m) => m.name);
  window.textured = [];
  gltf.scene.traverse((o) => { if (o.isMesh && o.material.map) window.textured.push(o.material.map.image.width); });
  window.ready = true;
}, undefined, (e) => { window.failed = String(e); });
</script></body></html>`;

const server = http.createServer((req, res) => {
  const url = decodeURIComponent(req.url.split('?')[0]);
  let file;
  if (url === '/') { res.writeHead(200, { 'Content-Type': 'text/html' }); res.end(page); return; }
  if (url === '/favicon.ico') { res.writeHead(204); res.end(); return; }
  if (url === '/model.glb') file = args.gltf;
  else if (url.startsWith('/three/') && !url.includes('..')) file = path.join(args.modules, url.slice(1));
  if (!file || !fs.existsSync(file)) { res.writeHead(404); res.end(); return; }
  res.writeHead(200, { 'Content-Type': file.endsWith('.js') ? 'text/javascript' : 'application/octet-stream' });
  fs.createReadStream(file).pipe(res);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const url = `http://127.0.0.1:${server.address().port}/`;

fs.mkdirSync(args.out, { recursive: true });
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'rad-gltf-chromium-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: CHROMIUM,
  headless: true,
  viewport: { width: 800, height: 600 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader', '--disable-background-networking', '--disable-component-update',
    '--disable-sync', '--no-first-run'],
});
try {
  const tab = context.pages()[0] ?? (await context.newPage());
  const errors = [];
  tab.on('pageerror', (e) => errors.push(e.message));
  tab.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await tab.goto(url);
  await tab.waitForFunction(() => window.ready || window.failed, null, { timeout: 30000 });
  const failed = await tab.evaluate(() => window.failed);
  check(!failed, `GLTFLoader loads the file${failed ? ': ' + failed : ''}`);
  const textured = await tab.evaluate(() => window.textured);
  check(textured.length === 3, `three.js shows ${textured.length} textured meshes (images ${textured.join(', ')} texels wide)`);
  // The floor's checker: square (i, j) (u, v = x, z in quarters) is the light colour (red)
  // where i + j is even, the dark one (blue) where it is odd.
  const blue = await tab.evaluate(() => window.pixelAt([0.125, 0, 0.875]));
  const red = await tab.evaluate(() => window.pixelAt([0.375, 0, 0.875]));
  check(red[0] > 1.5 * red[2] && red[0] > 40, `a light square of the floor is red ${fmt(red)}`);
  check(blue[2] > 1.5 * blue[0] && blue[2] > 40, `a dark square of the floor is blue ${fmt(blue)}`);
  // The light: a red square under the lamp against a red square in a corner.
  const under = await tab.evaluate(() => window.pixelAt([0.625, 0, 0.625]));
  const corner = await tab.evaluate(() => window.pixelAt([0.875, 0, 0.875]));
  check(luminance(under) > 1.08 * luminance(corner),
    `the floor under the lamp ${fmt(under)} is brighter than in the corner ${fmt(corner)}`);
  // The cut-out sign: its green disc shows, its transparent corner shows the wall behind.
  const disc = await tab.evaluate(() => window.pixelAt([0.5, 0.4, 0.3]));
  const hole = await tab.evaluate(() => window.pixelAt([0.32, 0.58, 0.3]));
  check(disc[1] > 1.3 * disc[0] && disc[1] > 1.3 * disc[2], `the sign's disc is green ${fmt(disc)}`);
  check(!(hole[1] > 1.3 * hole[0] && hole[1] > 1.3 * hole[2]), `the sign's cut-out corner is not ${fmt(hole)}`);
  const shot = path.join(args.out, 'texture_gltf.png');
  await tab.screenshot({ path: shot });
  console.log(`screenshot: ${shot}`);
  check(errors.length === 0, `no errors on the page${errors.length ? ': ' + errors.join(' | ') : ''}`);
} catch (e) {
  check(false, e.message);
} finally {
  await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
  server.close();
}
console.log(failures ? 'FAILED' : 'PASSED');
process.exit(failures ? 1 : 0);

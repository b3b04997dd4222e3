// End-to-end test of `rad serve` in headless Chromium (Debian's, driven by playwright-core):
// the page loads and shows the Cornell box (red left wall, green right wall, read back from the
// canvas), raising the light in the panel brightens the floor, clicking the floor in subdivide
// mode adds elements to it, and Ctrl-C writes --output. Saves a screenshot to look at.
//
//   node serve_e2e.mjs --rad build/rad --scene scenes/cornell_box.des \
//        --modules build/web/node_modules --out build/e2e
//
// Exits 0 on success, 1 on failure, 77 (ctest SKIP_RETURN_CODE) when Chromium or the npm
// modules are missing.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';

const SKIP = 77;
const CHROMIUM = '/usr/bin/chromium';
const args = Object.fromEntries(
  process.argv.slice(2).reduce((pairs, a, i, all) => (a.startsWith('--') ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
for (const k of ['rad', 'scene', 'modules', 'out']) {
  if (!args[k]) { console.error(`missing --${k}`); process.exit(2); }
}

function skip(why) {
  console.log(`SKIP: ${why} (install with: source tools/setup.sh && rad_install_web)`);
  process.exit(SKIP);
}
if (!fs.existsSync(CHROMIUM)) skip(`${CHROMIUM} not found`);
for (const m of ['playwright-core', 'three', 'lil-gui']) {
  if (!fs.existsSync(path.join(args.modules, m, 'package.json'))) skip(`npm module ${m} not found in ${args.modules}`);
}
const { chromium } = createRequire(path.resolve(args.modules, 'noop.js'))('playwright-core');

const started = Date.now();
const log = (...m) => console.log(`[${((Date.now() - started) / 1000).toFixed(1)}s]`, ...m);
let failures = 0;
function check(ok, what) {
  log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}
const luminance = ([r, g, b]) => 0.2126 * r + 0.7152 * g + 0.0722 * b;
const fmt = (c) => `(${c.map((x) => x.toFixed(0)).join(', ')})`;

fs.mkdirSync(args.out, { recursive: true });
const output = path.join(args.out, 'serve_exit.ply');
fs.rmSync(output, { force: true });

// ---------------------------------------------------------------- rad serve
const rad = spawn(args.rad, ['serve', args.scene, '--port', '0', '--output', output], {
  env: { ...process.env, RAD_WEB_MODULES: args.modules },
  stdio: ['ignore', 'pipe', 'pipe'],
});
let radOut = '';
rad.stdout.on('data', (d) => (radOut += d));
rad.stderr.on('data', (d) => (radOut += d));
const radExit = new Promise((resolve) => rad.on('exit', (code, signal) => resolve({ code, signal })));
const url = await new Promise((resolve, reject) => {
  const timer = setTimeout(() => reject(new Error(`rad serve printed no address:\n${radOut}`)), 30000);
  const look = () => {
    const m = radOut.match(/rad serve: (http:\/\/\S+)/);
    if (m) { clearTimeout(timer); resolve(m[1]); }
  };
  rad.stdout.on('data', look);
  rad.on('exit', () => reject(new Error(`rad serve exited:\n${radOut}`)));
});
log(`rad serve at ${url}`);

const watchdog = setTimeout(() => {
  console.error('FAIL: the test took longer than 100 s');
  rad.kill('SIGKILL');
  process.exit(1);
}, 100000);

// ---------------------------------------------------------------- the browser
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'rad-e2e-chromium-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: CHROMIUM,
  headless: true,
  viewport: { width: 1200, height: 760 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader', '--disable-background-networking', '--disable-component-update',
    '--disable-sync', '--no-first-run'],
});
try {
  const page = context.pages()[0] ?? (await context.newPage());
  const pageErrors = [];
  page.on('pageerror', (e) => pageErrors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') pageErrors.push(m.text()); });
  await page.goto(url);
  await page.waitForFunction(() => window.rad && window.rad.ready && window.rad.status, null, { timeout: 30000 });
  log('page loaded, mesh shown');
  const webgl = await page.evaluate(() => {
    const gl = document.getElementById('canvas').getContext('webgl2');
    return gl ? gl.getParameter(gl.RENDERER) : 'none';
  });
  log(`WebGL renderer: ${webgl}`);

  // Updates while solving: count snapshot events over two seconds.
  const n0 = await page.evaluate(() => window.rad.snapshots);
  await page.waitForTimeout(2000);
  const st = await page.evaluate(() => ({ n: window.rad.snapshots, s: window.rad.status.status }));
  check(st.n - n0 >= 3 || st.s !== 'running', `${st.n - n0} snapshot events in 2 s while ${st.s}`);

  // Let the light bounce a little before judging colours.
  await page.waitForFunction(() => window.rad.status.unshot_fraction < 0.15 && window.rad.colourVersion >= window.rad.status.version - 2,
    null, { timeout: 45000, polling: 200 });
  const progress = await page.evaluate(() => window.rad.status);
  log(`shots ${progress.shots}, unshot ${progress.unshot_fraction.toExponential(2)}, ${progress.elements} elements`);

  // The Cornell box seen from its open side: red wall on the left (x = 550), green on the right.
  const red = await page.evaluate(() => window.rad.pixelAt([550, 330, 330], 3));
  const green = await page.evaluate(() => window.rad.pixelAt([1, 330, 330], 3));
  const [rx] = await page.evaluate(() => window.rad.project([550, 330, 330]));
  const [gx] = await page.evaluate(() => window.rad.project([1, 330, 330]));
  check(rx < gx, `the red wall is left of the green wall on screen (x ${rx.toFixed(0)} < ${gx.toFixed(0)})`);
  check(red[0] > 60 && red[0] > 1.8 * red[1] && red[0] > 1.8 * red[2], `left wall is red ${fmt(red)}`);
  check(green[1] > 40 && green[1] > 1.3 * green[0] && green[1] > 1.3 * green[2], `right wall is green ${fmt(green)}`);

  // Raise the light in the panel: select it in the hierarchy, type a brighter emission.
  const floorPoint = [450, 0, 120];  // free floor in front of the short block
  const before = await page.evaluate((p) => window.rad.pixelAt(p, 4), floorPoint);
  await page.locator('.tree .item', { hasText: /^Plight/ }).first().click();
  const emissionInput = page.locator('[data-control=emission] input');
  await emissionInput.waitFor({ state: 'visible' });
  const e0 = parseFloat(await emissionInput.inputValue());
  check(Math.abs(e0 - 53.407) < 0.01, `the light's emission shows ${e0}`);
  const shotsAtEdit = await page.evaluate(() => window.rad.status.shots);
  await emissionInput.fill(String(+(3 * e0).toFixed(2)));
  await emissionInput.press('Enter');
  await page.waitForFunction((e) => {
    const s = window.rad.status, light = s.objects[window.rad.objectId('light')];
    return Math.abs(light.emission - e) < 0.01;
  }, 3 * e0, { timeout: 10000, polling: 100 });
  log('the server took the new emission; waiting for the solve to spread it');
  await page.waitForFunction((n) => {
    const s = window.rad.status;
    return (s.status === 'converged' || s.shots >= n + 12) && window.rad.colourVersion >= s.version - 1;
  }, shotsAtEdit, { timeout: 45000, polling: 200 });
  const after = await page.evaluate((p) => window.rad.pixelAt(p, 4), floorPoint);
  check(luminance(after) > 1.25 * luminance(before) && luminance(after) > luminance(before) + 15,
    `floor brightens with the light: ${fmt(before)} -> ${fmt(after)}`);

  // Click the floor in subdivide mode: its element count grows.
  await page.locator('[data-control=click-mode] select').selectOption({ label: 'subdivide polygon' });
  const floorBefore = await page.evaluate(() => window.rad.elements('floor'));
  const box = await page.locator('#canvas').boundingBox();
  const [fx, fy] = await page.evaluate((p) => window.rad.project(p), floorPoint);
  await page.mouse.click(box.x + fx, box.y + fy);
  await page.waitForFunction((n) => window.rad.elements('floor') > n, floorBefore, { timeout: 20000, polling: 100 });
  const floorAfter = await page.evaluate(() => window.rad.elements('floor'));
  const notice = await page.locator('#notice').textContent();
  check(floorAfter > floorBefore, `clicking the floor subdivides it: ${floorBefore} -> ${floorAfter} elements ("${notice}")`);
  const selectedName = await page.locator('.tree .item.selected .name').textContent();
  check(selectedName === 'floor', `the clicked object is selected in the panel (${selectedName})`);

  // Exports of the current snapshot answer from the page's origin.
  const exports = await page.evaluate(async () => {
    const out = {};
    for (const f of ['ply', 'glb', 'png?size=64x64']) {
      const r = await fetch(`/api/export.${f}`);
      out[f] = [r.status, (await r.arrayBuffer()).byteLength];
    }
    return out;
  });
  check(Object.values(exports).every(([s, n]) => s === 200 && n > 0), `exports: ${JSON.stringify(exports)}`);

  await page.waitForTimeout(300);
  const shot = path.join(args.out, 'serve_e2e.png');
  await page.screenshot({ path: shot });
  log(`screenshot: ${shot}`);
  check(pageErrors.length === 0, `no errors on the page${pageErrors.length ? ': ' + pageErrors.join(' | ') : ''}`);
} catch (e) {
  check(false, `${e.message}`);
} finally {
  await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
}

// ---------------------------------------------------------------- Ctrl-C writes --output
rad.kill('SIGINT');
const exit = await radExit;
clearTimeout(watchdog);
check(exit.code === 0, `rad serve exits 0 on SIGINT (code ${exit.code}, signal ${exit.signal})`);
check(fs.existsSync(output) && fs.statSync(output).size > 1000, `--output written on exit: ${output}`);
if (failures) console.log(radOut.split('\n').slice(-15).join('\n'));
console.log(`${failures ? 'FAILED' : 'PASSED'} in ${((Date.now() - started) / 1000).toFixed(1)} s`);
process.exit(failures ? 1 : 0);

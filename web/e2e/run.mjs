// End-to-end tests of the modeler against the real `holey serve`.
//
//   cd web && npm run build && npm run test:e2e
//
// Env: HOLEY_BIN (default <repo>/target/release/holey), CHROMIUM (default
// /usr/bin/chromium), HOLEY_MESHES (default <repo>/../shared/data/meshes).
// `--mock` runs against e2e/mock-server.mjs instead (front-end development
// only; several scenarios need the real server). `--only N,M` picks scenarios.
//
// The real server prints its URL with the access token it made at start
// (`http://127.0.0.1:PORT/?token=HEX`); the tests open exactly that URL, as
// a user would, so the page load sets the token cookie the front end's
// requests then carry. Before the scenarios, the run checks that the server
// refuses a request without the token.
//
// Screenshots and perf.json go to web/e2e/artifacts/ (CI's artifact folder);
// a failing scenario also prints the strokes it sent and writes them there
// as a stroke file (scenario-N-strokes.json) for the frame_trace example.
// Every scenario prints PASS/FAIL/SKIP; the exit code is non-zero on any FAIL.

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import readline from 'node:readline';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = path.dirname(fileURLToPath(import.meta.url));
const webDir = path.resolve(here, '..');
const repo = path.resolve(webDir, '..');
const dist = path.join(webDir, 'dist');
const artifacts = path.join(here, 'artifacts');
const meshesDir = process.env.HOLEY_MESHES || path.resolve(repo, '../shared/data/meshes');
const useMock = process.argv.includes('--mock');
const onlyArg = process.argv.indexOf('--only');
const only = onlyArg >= 0 ? new Set(process.argv[onlyArg + 1].split(',').map(Number)) : null;

fs.mkdirSync(artifacts, { recursive: true });
if (!fs.existsSync(path.join(dist, 'index.html'))) {
  console.error(`FAIL: ${dist}/index.html is missing; run \`npm run build\` in web/ first`);
  process.exit(1);
}

// ---- server ---------------------------------------------------------------

function startServer() {
  const stateDir = fs.mkdtempSync(path.join(os.tmpdir(), 'holey-e2e-'));
  let cmd, args;
  if (useMock) {
    cmd = process.execPath;
    args = [path.join(here, 'mock-server.mjs'), '--port', '0', '--web', dist];
  } else {
    cmd = process.env.HOLEY_BIN || path.join(repo, 'target/release/holey');
    if (!fs.existsSync(cmd)) throw new Error(`${cmd} not found: build it with \`cargo build --release\` (or set HOLEY_BIN)`);
    // No --web, and started outside the repository: the page must come
    // from the front end embedded in the binary, as for an installed one.
    args = ['serve', '--port', '0', '--state-dir', stateDir];
  }
  const child = spawn(cmd, args, { cwd: stateDir, stdio: ['ignore', 'pipe', 'pipe'] });
  let log = '';
  child.stderr.on('data', (d) => { log += d; });
  const url = new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`server printed no URL within 30 s\n${log}`)), 30000);
    readline.createInterface({ input: child.stdout }).on('line', (line) => {
      log += line + '\n';
      const m = /holey serve: listening on (http:\/\/\S+)/.exec(line);
      if (m) {
        clearTimeout(timer);
        resolve(m[1]);
      }
    });
    child.on('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`server exited with ${code} before listening\n${log}`));
    });
  });
  return { child, url, stateDir, log: () => log };
}

/**
 * The real server admits nothing without its token (issue 17): the printed
 * URL must carry one, the API must refuse a request without it and accept
 * the same request with it.
 */
async function checkAccess(url) {
  const token = new URL(url).searchParams.get('token');
  if (!token) throw new Error(`the printed URL carries no ?token=: ${url}`);
  const health = new URL('api/health', url);
  const without = await fetch(health);
  if (without.status !== 403) throw new Error(`GET /api/health without the token answered ${without.status}, not 403`);
  const withHeader = await fetch(health, { headers: { Authorization: `token ${token}` } });
  if (withHeader.status !== 200) throw new Error(`GET /api/health with the token answered ${withHeader.status}, not 200`);
}

// ---- helpers ------------------------------------------------------------------

const tid = (id) => `[data-testid="${id}"]`;

/** page.waitForFunction with a failure message that says what was awaited. */
async function waitFor(page, what, fn, arg, timeout = 30000) {
  try {
    await page.waitForFunction(fn, arg, { timeout, polling: 50 });
  } catch (e) {
    const h = await page.evaluate(() => ({
      version: window.__holey?.version, frameVersion: window.__holey?.frameVersion,
      workspace: window.__holey?.state?.workspace, busy: window.__holey?.state?.busy,
      stroking: window.__holey?.strokeInfo, pending: window.__holey?.pending, errors: window.__holey?.errors,
    })).catch(() => ({}));
    throw new Error(`timed out (${timeout / 1000} s) waiting for ${what}; page: ${JSON.stringify(h)}${await lastToast(page)}`);
  }
}
const genusRe = (g) => new RegExp(`genus ${g}(?!\\d)`);

async function statsText(page) {
  return page.textContent(tid('stats'));
}

async function waitStats(page, re, timeout = 30000) {
  try {
    await page.waitForFunction(
      ([src, flags]) => new RegExp(src, flags).test(document.querySelector('[data-testid="stats"]').textContent),
      [re.source, re.flags],
      { timeout, polling: 100 },
    );
  } catch {
    throw new Error(`stats never matched ${re}; they show "${await statsText(page)}"${await lastToast(page)}`);
  }
}

async function lastToast(page) {
  const errs = await page.$$eval(tid('toast-error'), (els) => els.map((e) => e.textContent));
  return errs.length ? `; error toasts: ${errs.join(' | ')}` : '';
}

/** Wait until the page has a frame/state newer than `v` (and no stroke running). */
async function waitVersionAbove(page, v, timeout = 30000) {
  await waitFor(page, `a document version above ${v}`,
    (old) => window.__holey.version > old && window.__holey.frameVersion === window.__holey.version, v, timeout);
}

const version = (page) => page.evaluate(() => window.__holey.version);

async function setWorkspace(page, ws) {
  await page.click(tid(`workspace-${ws}`));
  await waitFor(page, `the ${ws} workspace`, (w) => window.__holey.state?.workspace === w, ws);
  await waitFor(page, 'the frame of the current version', () => window.__holey.frameVersion === window.__holey.version);
}

async function createPrimitive(page, spec) {
  const v = await version(page);
  const options = await page.$$eval(`${tid('primitive-select')} option`, (os) => os.map((o) => o.value));
  if (!options.includes(spec)) throw new Error(`primitive ${spec} is not offered (offered: ${options.join(' ')})`);
  await page.selectOption(tid('primitive-select'), spec);
  await page.click(tid('primitive-create'));
  await waitVersionAbove(page, v);
}

/** Clicks the button `id` and waits for the document version it makes. */
async function clickForNewVersion(page, id, timeout = 30000) {
  const v = await version(page);
  await page.click(tid(id));
  await waitVersionAbove(page, v, timeout);
}

/** The model workspace showing the primitive `spec`, once the stats match
 * `re`; returns the stats parsed. */
async function modelOf(page, spec, re) {
  await setWorkspace(page, 'model');
  await createPrimitive(page, spec);
  await waitStats(page, re);
  return parseStats(await statsText(page));
}

/** Face picking, the view from `dir`, and a click on the surface at the
 * world point `p`: one face selected. Returns the point clicked on screen. */
async function pickFaceAt(page, dir, p) {
  await page.check('[name=pick][value=face]');
  await page.evaluate((d) => window.__holey.setView(d), dir);
  await page.waitForTimeout(100);
  const at = await page.evaluate((q) => window.__holey.project(q), p);
  await page.mouse.click(at[0], at[1]);
  await waitFor(page, 'one selected face', () => window.__holey.selection.faces.length === 1);
  return at;
}

/** Each face of a frame's arrays (`window.__holey.frameArrays`) as its
 * area vector (the sum of its triangles') and centroid direction (the sum
 * of its triangles' corners), from the triangles alone. */
function faceFrames({ positions: p, tris, triFace, nf }) {
  const faces = Array.from({ length: nf }, () => ({ normal: [0, 0, 0], centre: [0, 0, 0] }));
  for (let t = 0; t < triFace.length; t++) {
    const [a, b, c] = [0, 1, 2].map((k) => [0, 1, 2].map((i) => p[3 * tris[3 * t + k] + i]));
    const u = [0, 1, 2].map((i) => b[i] - a[i]), w = [0, 1, 2].map((i) => c[i] - a[i]);
    const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
    const f = faces[triFace[t]];
    for (let i = 0; i < 3; i++) {
      f.normal[i] += n[i];
      f.centre[i] += a[i] + b[i] + c[i];
    }
  }
  return faces;
}
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/** Six cubes of side 1 centred on the axes at distance 3, as OBJ text. */
function sixCubesObj() {
  const corners = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];
  const quads = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]];
  let text = '';
  for (let k = 0; k < 6; k++) {
    const axis = k >> 1, side = k % 2 ? 3 : -3;
    for (const c of corners) text += `v ${c.map((x, i) => x - 0.5 + (i === axis ? side : 0)).join(' ')}\n`;
    for (const q of quads) text += `f ${q.map((i) => 8 * k + i + 1).join(' ')}\n`;
  }
  return text;
}

async function setRange(page, id, value) {
  await page.$eval(tid(id), (el, val) => {
    el.value = String(val);
    el.dispatchEvent(new Event('input', { bubbles: true }));
    el.dispatchEvent(new Event('change', { bubbles: true }));
  }, value);
}

/** Parse "V 8 · E 12 · F 6 · … genus 0 …" into numbers. */
function parseStats(text) {
  const get = (re) => Number(re.exec(text)?.[1]);
  return { V: get(/\bV (\d+)/), E: get(/\bE (\d+)/), F: get(/\bF (\d+)/), genus: get(/genus (-?\d+)/) };
}

const median = (xs) => (xs.length ? [...xs].sort((a, b) => a - b)[xs.length >> 1] : null);
const pct = (xs, p) => (xs.length ? [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(xs.length * p))] : null);
const round = (x, d = 1) => (x == null ? null : Math.round(x * 10 ** d) / 10 ** d);

// ---- the sculpt workspace's helpers ---------------------------------------------

/** A fresh @sphere (level 3: 642 vertices on the unit sphere) in the sculpt
 * workspace, seen from the front, remeshing off so vertex numbers stay. */
async function sculptSphere(page) {
  await setWorkspace(page, 'model');
  await createPrimitive(page, '@sphere');
  await setWorkspace(page, 'sculpt');
  await setRange(page, 'remesh-detail', 0);
  await waitFor(page, 'remeshing off', () => window.__holey.state?.remesh?.detail === 0);
  if (await page.evaluate(() => window.__holey.camera.ortho)) await page.uncheck(tid('ortho-toggle'));
  await page.evaluate(() => window.__holey.setView([0, 0, 1]));
  await page.waitForTimeout(100);
}

/** The positions the page shows (the server's frames, f32). */
const positions = (page) => page.evaluate(() => window.__holey.positions);

/** Drag the mouse from one world point to another (projected to the
 * screen) in `steps` moves, holding `modifiers`; waits for the stroke's end. */
async function dragThrough(page, from, to, { steps = 12, modifiers = [] } = {}) {
  const a = await page.evaluate((p) => window.__holey.project(p), from);
  const b = await page.evaluate((p) => window.__holey.project(p), to);
  for (const m of modifiers) await page.keyboard.down(m);
  await page.mouse.move(a[0], a[1]);
  await page.mouse.down();
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(a[0] + ((b[0] - a[0]) * i) / steps, a[1] + ((b[1] - a[1]) * i) / steps);
    await page.waitForTimeout(15);
  }
  await page.mouse.up();
  for (const m of modifiers) await page.keyboard.up(m);
  await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
}

/** Indices of the vertices whose position differs (same vertex count). */
function movedVertices(before, after) {
  if (before.length !== after.length) throw new Error(`the vertex count changed: ${before.length / 3} -> ${after.length / 3}`);
  const out = [];
  for (let k = 0; k < before.length / 3; k++) {
    if (before[3 * k] !== after[3 * k] || before[3 * k + 1] !== after[3 * k + 1] || before[3 * k + 2] !== after[3 * k + 2]) out.push(k);
  }
  return out;
}

const norm = (p, k) => Math.hypot(p[3 * k], p[3 * k + 1], p[3 * k + 2]);

/** The largest distance from a vertex's mirror image across x = 0 to the
 * nearest vertex. */
function mirrorDistance(p) {
  let worst = 0;
  for (let i = 0; i < p.length; i += 3) {
    let best = Infinity;
    for (let j = 0; j < p.length; j += 3) {
      const d = Math.hypot(p[j] + p[i], p[j + 1] - p[i + 1], p[j + 2] - p[i + 2]);
      if (d < best) best = d;
    }
    worst = Math.max(worst, best);
  }
  return worst;
}

/** The largest distance from a vertex's mirror image across the plane
 * `axis` (0, 1, 2) = `c` to the nearest vertex (flat xyz array). */
function mirrorDistanceAcross(p, axis, c) {
  let worst = 0;
  for (let i = 0; i < p.length; i += 3) {
    const q = [p[i], p[i + 1], p[i + 2]];
    q[axis] = 2 * c - q[axis];
    let best = Infinity;
    for (let j = 0; j < p.length; j += 3) {
      const d = Math.hypot(p[j] - q[0], p[j + 1] - q[1], p[j + 2] - q[2]);
      if (d < best) best = d;
    }
    worst = Math.max(worst, best);
  }
  return worst;
}

/** Drag the mouse through world points (projected to the screen), `steps`
 * moves between each two, as one stroke; waits for the stroke's end. */
async function dragPath(page, points, { steps = 12, pause = 15 } = {}) {
  const px = [];
  for (const p of points) px.push(await page.evaluate((q) => window.__holey.project(q), p));
  await page.mouse.move(px[0][0], px[0][1]);
  await page.mouse.down();
  for (let j = 1; j < px.length; j++) {
    const [a, b] = [px[j - 1], px[j]];
    for (let i = 1; i <= steps; i++) {
      await page.mouse.move(a[0] + ((b[0] - a[0]) * i) / steps, a[1] + ((b[1] - a[1]) * i) / steps);
      await page.waitForTimeout(pause);
    }
  }
  await page.mouse.up();
  await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
}

/** Renders the 3D view whole and keeps its pixels in the page
 * (`window.__e2ePicture`), or with `compare` counts the pixels whose
 * luma differs from the kept picture by more than 4 levels in 255 (the
 * pictures are drawn alike, so any difference is the mesh's). */
async function viewPicture(page, compare = false) {
  return page.evaluate(async (cmp) => {
    const img = new Image();
    img.src = window.__holey.viewer.screenshot();
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    const luma = new Float32Array(c.width * c.height);
    for (let i = 0; i < luma.length; i++) luma[i] = 0.2126 * d[4 * i] + 0.7152 * d[4 * i + 1] + 0.0722 * d[4 * i + 2];
    if (!cmp) {
      window.__e2ePicture = luma;
      return 0;
    }
    const old = window.__e2ePicture;
    let n = 0;
    for (let i = 0; i < luma.length; i++) if (Math.abs(luma[i] - old[i]) > 4) n++;
    return n;
  }, compare);
}

/** The 3D view's luma (0–255) at world points, each averaged over 5×5
 * pixels, drawn whole. */
async function lumaAt(page, points) {
  return page.evaluate(async (pts) => {
    const v = window.__holey.viewer;
    const img = new Image();
    img.src = v.screenshot();
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const r = v.canvas.getBoundingClientRect();
    return pts.map((p) => {
      const [x, y] = v.project(p);
      const px = Math.round(((x - r.left) * c.width) / r.width), py = Math.round(((y - r.top) * c.height) / r.height);
      const d = ctx.getImageData(px - 2, py - 2, 5, 5).data;
      let sum = 0;
      for (let i = 0; i < 25; i++) sum += 0.2126 * d[4 * i] + 0.7152 * d[4 * i + 1] + 0.0722 * d[4 * i + 2];
      return sum / 25;
    });
  }, points);
}

/** The farthest any position of `after` lies from the nearest position of
 * `before` (flat xyz arrays; a grid of `cell`-wide boxes, searched ring by
 * ring), a lower bound for how far the surface moved. */
function farthestMove(before, after, cell) {
  const key = (x, y, z) => `${Math.floor(x / cell)},${Math.floor(y / cell)},${Math.floor(z / cell)}`;
  const grid = new Map();
  for (let i = 0; i < before.length; i += 3) {
    const k = key(before[i], before[i + 1], before[i + 2]);
    if (!grid.has(k)) grid.set(k, []);
    grid.get(k).push(i);
  }
  let worst = 0;
  for (let j = 0; j < after.length; j += 3) {
    const [x, y, z] = [after[j], after[j + 1], after[j + 2]];
    const [cx, cy, cz] = [Math.floor(x / cell), Math.floor(y / cell), Math.floor(z / cell)];
    let best = Infinity;
    // Ring r holds every point within r·cell; stop once the best beats it.
    for (let r = 0; r < 64 && !(best <= r * cell); r++) {
      for (let a = -r; a <= r; a++) for (let b = -r; b <= r; b++) for (let c = -r; c <= r; c++) {
        if (Math.max(Math.abs(a), Math.abs(b), Math.abs(c)) !== r) continue;
        for (const i of grid.get(`${cx + a},${cy + b},${cz + c}`) || []) {
          const d = Math.hypot(before[i] - x, before[i + 1] - y, before[i + 2] - z);
          if (d < best) best = d;
        }
      }
    }
    if (best > worst) worst = best;
  }
  return worst;
}

// ---- the strokes a scenario sent -----------------------------------------------

// Where a mouse stroke's dabs fall depends on the picture the page had
// when each pointer event came, so a failing stroke is kept as sent: the
// scenario's strokes, as a stroke file (crates/sculpt/src/strokes.rs),
// are printed with a failure and written to artifacts, to be replayed
// frame by frame with `frame_trace MESH FILE` (crates/sculpt/examples).
const sentStrokes = [];
// The id of the last stroke_begin sent: its answer names the range the
// stroke remeshes to, derived from the mesh as it began, which the
// stroke file records per stroke (`remesh`) for the replay.
let beginId = null;

function keepAnswer(text) {
  if (beginId === null || !text.includes('"remesh"')) return;
  let m;
  try { m = JSON.parse(text); } catch { return; }
  if (m.type === 'ok' && m.id === beginId && m.remesh !== undefined && sentStrokes.length) {
    sentStrokes[sentStrokes.length - 1].remesh = m.remesh;
    beginId = null;
  }
}

function keepStroke(text) {
  if (!text.includes('"op":"stroke_')) return;
  let m;
  try { m = JSON.parse(text); } catch { return; }
  if (m.op === 'stroke_begin') {
    // `frames`: the dabs of each request, which the server paints as one
    // frame (stroke_begin's point is the first).
    const s = { brush: m.brush, radius: m.radius, path: [m.point], frames: [1] };
    if (m.brush !== 'move' && m.strength !== undefined) s.strength = m.strength;
    if (m.falloff) s.falloff = m.falloff;
    if (m.symmetry) s.symmetry = m.symmetry;
    if (m.symmetry_about) s.symmetry_about = m.symmetry_about;
    sentStrokes.push(s);
    beginId = m.id;
  } else if (m.op === 'stroke_frame' && sentStrokes.length) {
    const s = sentStrokes[sentStrokes.length - 1];
    s.path.push(m.point, ...(m.points || []));
    s.frames.push(1 + (m.points || []).length);
  }
}

// Every scenario's strokes are written, so that a failure that depends on
// an earlier scenario's strokes on the same mesh can be replayed whole;
// they are printed only with a failure.
function keepStrokes(n, failed) {
  if (!sentStrokes.length) return;
  const text = JSON.stringify({ strokes: sentStrokes });
  fs.writeFileSync(path.join(artifacts, `scenario-${n}-strokes.json`), text + '\n');
  if (failed) console.log(`  the scenario's strokes as sent (scenario-${n}-strokes.json): ${text}`);
}

// ---- scenarios ------------------------------------------------------------------

const consoleErrors = [];
const perf = {};

const scenarios = [
  ['page loads with no console errors', async (page, url) => {
    await page.goto(url);
    await page.waitForFunction(() => window.__holey?.frames > 0 && window.__holey.stats, null, { timeout: 30000 });
    await page.waitForFunction(() => document.querySelectorAll('[data-testid="primitive-select"] option').length > 0, null, { timeout: 10000 });
    await page.waitForTimeout(300);
    if (consoleErrors.length) throw new Error(`console errors: ${consoleErrors.join(' | ')}`);
    const text = await statsText(page);
    if (!/genus \d+/.test(text)) throw new Error(`stats do not show a genus: "${text}"`);
  }],

  ['@torus shows genus 1', async (page) => {
    await setWorkspace(page, 'model');
    await createPrimitive(page, '@torus');
    await waitStats(page, genusRe(1));
  }],

  ['Sierpinski level 1 of a tetrahedron shows genus 3', async (page) => {
    await setWorkspace(page, 'model');
    await createPrimitive(page, '@tetrahedron');
    await waitStats(page, genusRe(0));
    await page.fill(tid('sierpinski-level'), '1');
    await clickForNewVersion(page, 'op-sierpinski');
    await waitStats(page, genusRe(3));
  }],

  ['grab stroke pokes the top of @sphere through the bottom: genus 1', async (page) => {
    await setWorkspace(page, 'model');
    await createPrimitive(page, '@sphere');
    await setWorkspace(page, 'sculpt');
    await waitStats(page, genusRe(0));
    await page.click(tid('tool-grab'));
    const box = await page.evaluate(() => window.__holey.bbox);
    const r = (box.max[1] - box.min[1]) / 2;
    const c = box.center;
    // Brush radius 0.4 sphere radii, given to the slider in % of the diagonal.
    await setRange(page, 'radius', Math.round(((0.4 * r) / box.diag) * 1000) / 10);
    await setRange(page, 'strength', 1);
    await page.evaluate(() => window.__holey.setView([0, 0, 1]));
    await page.waitForTimeout(100);
    // Press just below the top of the sphere as seen from the front, then
    // drag (in the camera plane through that point) well past the bottom.
    const y0 = 0.92, z0 = Math.sqrt(1 - y0 * y0);
    const start = await page.evaluate((p) => window.__holey.project(p), [c[0], c[1] + y0 * r, c[2] + z0 * r]);
    const end = await page.evaluate((p) => window.__holey.project(p), [c[0], c[1] - 1.6 * r, c[2] + z0 * r]);
    const v = await version(page);
    await page.mouse.move(start[0], start[1]);
    await page.mouse.down();
    const steps = 40;
    for (let i = 1; i <= steps; i++) {
      await page.mouse.move(start[0] + ((end[0] - start[0]) * i) / steps, start[1] + ((end[1] - start[1]) * i) / steps);
      await page.waitForTimeout(25);
    }
    await page.waitForTimeout(300);
    await page.screenshot({ path: path.join(artifacts, '4-grab-preview.png') });
    await page.mouse.up();
    await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
    await waitVersionAbove(page, v);
    await waitStats(page, genusRe(1));
  }],

  ['undo brings genus 0 back', async (page) => {
    await clickForNewVersion(page, 'undo');
    await waitStats(page, genusRe(0));
    // Keyboard redo/undo too.
    await page.locator(tid('canvas')).focus();
    const v2 = await version(page);
    await page.keyboard.press('Control+Shift+Z');
    await waitVersionAbove(page, v2);
    await waitStats(page, genusRe(1));
    const v3 = await version(page);
    await page.keyboard.press('Control+Z');
    await waitVersionAbove(page, v3);
    await waitStats(page, genusRe(0));
  }],

  ['import a shared mesh through the file picker', async (page) => {
    const file = path.join(meshesDir, 'fertility_poly.obj');
    if (!fs.existsSync(file)) return 'SKIP';
    await setWorkspace(page, 'model');
    const v = await version(page);
    await page.setInputFiles(tid('import-input'), file);
    await waitVersionAbove(page, v);
    // shared/data/meshes/README.md: V 3730, F 2048 polygons, closed, genus 4.
    await waitStats(page, /V 3730\b.*F 2048\b.*genus 4(?!\d)/);
  }],

  ['export OBJ and import it again: same V, F and genus', async (page) => {
    const before = parseStats(await statsText(page));
    await page.selectOption(tid('export-format'), 'obj');
    const [download] = await Promise.all([page.waitForEvent('download', { timeout: 30000 }), page.click(tid('export'))]);
    const saved = path.join(artifacts, 'export-roundtrip.obj');
    await download.saveAs(saved);
    if (fs.statSync(saved).size === 0) throw new Error('the exported file is empty');
    const v = await version(page);
    await page.setInputFiles(tid('import-input'), saved);
    await waitVersionAbove(page, v);
    await page.waitForTimeout(200);
    const after = parseStats(await statsText(page));
    if (JSON.stringify([before.V, before.F, before.genus]) !== JSON.stringify([after.V, after.F, after.genus])) {
      throw new Error(`before ${JSON.stringify(before)} after ${JSON.stringify(after)}`);
    }
  }],

  ['export GLB and import it again: same V and genus, the faces as triangles', async (page) => {
    if (useMock) return 'SKIP'; // the mock server exports OBJ only
    const before = await page.evaluate(() => window.__holey.stats);
    await page.selectOption(tid('export-format'), 'glb');
    const [download] = await Promise.all([page.waitForEvent('download', { timeout: 30000 }), page.click(tid('export'))]);
    if (download.suggestedFilename() !== 'holey.glb') throw new Error(`downloaded as ${download.suggestedFilename()}, not holey.glb`);
    const saved = path.join(artifacts, 'export-roundtrip.glb');
    await download.saveAs(saved);
    const magic = fs.readFileSync(saved).subarray(0, 4).toString('latin1');
    if (magic !== 'glTF') throw new Error(`the exported file starts with ${JSON.stringify(magic)}, not the GLB magic "glTF"`);
    const v = await version(page);
    await page.setInputFiles(tid('import-input'), saved);
    await waitVersionAbove(page, v);
    // glTF holds triangles: every polygon comes back as its triangles, the
    // vertices and the genus unchanged.
    const want = [before.vertices, before.triangles, before.genus];
    await waitFor(page, `V, F, genus ${JSON.stringify(want)} after importing the GLB`,
      (w) => { const s = window.__holey.stats; return !!s && s.vertices === w[0] && s.faces === w[1] && s.genus === w[2]; }, want);
  }],

  ['performance: orbit fps at ~1M triangles, sculpt latency at ~100k', async (page) => {
    // @sphere:L has 20·4^L triangles: L=8 → 1.31M, L=6 → 82k.
    await setWorkspace(page, 'model');
    let v = await version(page);
    await page.evaluate(() => window.__holey.request('primitive', { spec: '@sphere:8' }));
    await waitVersionAbove(page, v, 120000);
    const big = await page.evaluate(() => window.__holey.triangles);
    await page.evaluate(() => window.__holey.setView());
    await page.waitForTimeout(300);
    // At rest: the full mesh at full resolution (GPU waited for each picture).
    const rest = await page.evaluate(() => window.__holey.benchRender(5));
    // Orbit drawing the full mesh every frame (what the page did before the
    // proxy), then as a real orbit draws: motion resolution + proxy.
    const full = await page.evaluate(() => window.__holey.benchOrbit(8, { proxy: false }));
    const orbit = await page.evaluate(() => window.__holey.benchOrbit(90, { proxy: true }));
    const proxy = await page.evaluate(() => window.__holey.proxy);
    perf.orbit = {
      triangles: big,
      fullRenderMs: round(rest.medianMs), fullPixelRatio: rest.pixelRatio,
      orbitFpsFull: round(full.fps), orbitFullRenderMs: round(full.medianRenderMs),
      orbitFpsProxy: round(orbit.fps), orbitProxyRenderMs: round(orbit.medianRenderMs),
      proxyShown: orbit.proxyShown, proxyTriangles: orbit.proxyTriangles, proxyBuildMs: round(proxy.buildMs),
      motionPixelRatio: orbit.pixelRatio,
    };
    // A real mouse orbit through OrbitControls, counting rendered pictures,
    // with a screenshot while the button is held (proxy) and one at rest.
    const vp = page.viewportSize();
    const r0 = await page.evaluate(() => window.__holey.renders);
    const t0 = Date.now();
    await page.mouse.move(vp.width - 40, 80);
    await page.mouse.down({ button: 'right' });
    for (let i = 0; i < 40; i++) await page.mouse.move(vp.width - 40 - i * 6, 80 + i);
    const mouseMs = Date.now() - t0;
    perf.orbit.mouseDragPictures = (await page.evaluate(() => window.__holey.renders)) - r0;
    perf.orbit.mouseDragFps = round((perf.orbit.mouseDragPictures * 1000) / mouseMs);
    perf.orbit.mouseDragProxyShown = (await page.evaluate(() => window.__holey.proxy)).shown;
    await page.screenshot({ path: path.join(artifacts, '8-orbit-proxy.png') });
    await page.mouse.up({ button: 'right' });
    await waitFor(page, 'the full mesh after the orbit', () => !window.__holey.proxy.shown && !window.__holey.proxy.motion.length);
    await page.waitForTimeout(200);
    await page.screenshot({ path: path.join(artifacts, '8-rest-full.png') });
    if (!perf.orbit.proxyShown || !perf.orbit.mouseDragProxyShown) throw new Error(`the proxy was not drawn during the orbit: ${JSON.stringify(perf.orbit)}`);

    v = await version(page);
    // HOLEY_E2E_SCULPT_SPEC=@sphere:8 sculpts 1.31M triangles instead of 82k
    // (a measurement, not part of the suite's run).
    const sculptSpec = process.env.HOLEY_E2E_SCULPT_SPEC || '@sphere:6';
    await page.evaluate((spec) => window.__holey.request('primitive', { spec }), sculptSpec);
    await waitVersionAbove(page, v, 60000);
    await setWorkspace(page, 'sculpt');
    const mid = await page.evaluate(() => window.__holey.triangles);
    // Inflate by default (the UI scales its strength to the brush radius);
    // HOLEY_E2E_BRUSH=smooth|grab|move picks another brush.
    const brush = process.env.HOLEY_E2E_BRUSH || 'inflate';
    await page.click(tid(`tool-${brush}`));
    await setRange(page, 'radius', 8);
    await setRange(page, 'strength', 0.5);
    await page.evaluate(() => window.__holey.setView([0, 0, 1]));
    await page.waitForTimeout(100);
    const box = await page.evaluate(() => window.__holey.bbox);
    const c = await page.evaluate((p) => window.__holey.project(p), box.center);
    const rpx = (await page.evaluate((p) => window.__holey.project(p), [box.center[0] + (box.max[0] - box.center[0]), box.center[1], box.center[2]]))[0] - c[0];
    const KEYS = ['strokeLatencies', 'waitMs', 'roundTripMs', 'serverMs', 'clientMs', 'toRenderMs', 'renderMs', 'drawnTriangles'];
    const stroke = async (yOff, measureGpu) => {
      await page.evaluate(([keys, gpu]) => {
        const h = window.__holey;
        for (const k of keys) h[k].length = 0;
        h.positionsOnlyFrames = h.sparseFrames = 0;
        h.measureGpu = gpu;
      }, [KEYS, measureGpu]);
      const y = c[1] + yOff * rpx;
      await page.mouse.move(c[0] - 0.7 * rpx, y);
      await page.mouse.down();
      for (let i = 0; i <= 60; i++) {
        await page.mouse.move(c[0] + (-0.7 + (1.4 * i) / 60) * rpx, y + 0.4 * rpx * Math.sin((i / 60) * Math.PI));
        await page.waitForTimeout(16);
      }
      await page.mouse.up();
      await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
      const h = await page.evaluate((keys) => {
        const o = Object.fromEntries(keys.map((k) => [k, [...window.__holey[k]]]));
        o.positionsOnlyFrames = window.__holey.positionsOnlyFrames;
        o.sparseFrames = window.__holey.sparseFrames;
        window.__holey.measureGpu = false;
        return o;
      }, KEYS);
      return h;
    };
    // Measured: the page waits for the GPU (gl.finish) after each stroke
    // picture, so latency ends when the picture is really drawn.
    const m = await stroke(-0.2, true);
    // Not measured that way: latency ends when the draw calls were issued.
    const q = await stroke(0.3, false);
    const lat = m.strokeLatencies;
    // Partial redraws: during a stroke only the rectangle the brush changed
    // is drawn again. Mid-stroke, the picture built that way must equal a
    // full redraw of the same state.
    const p0 = await page.evaluate(() => window.__holey.partial);
    {
      const y = c[1] + 0.05 * rpx;
      await page.mouse.move(c[0] - 0.5 * rpx, y);
      await page.mouse.down();
      for (let i = 0; i <= 30; i++) {
        await page.mouse.move(c[0] + (-0.5 + i / 30) * rpx, y - 0.3 * rpx * Math.sin((i / 30) * Math.PI));
        await page.waitForTimeout(16);
      }
      await waitFor(page, 'the stroke frames to be answered', () => {
        const s = window.__holey.strokeInfo;
        return s && !s.inflight && !s.queued;
      });
      await page.waitForTimeout(100);
      perf.partial = await page.evaluate(() => window.__holey.comparePartialToFull());
      perf.partial.partialRendersInStroke = perf.partial.partialRenders - p0.renders;
      perf.partial.lastPartialTriangles = (await page.evaluate(() => window.__holey.partial)).triangles;
      await page.screenshot({ path: path.join(artifacts, '8-partial-check.png') });
      await page.mouse.up();
      await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
    }
    console.log(`  partial redraw check: ${JSON.stringify(perf.partial)}`);
    if (p0.enabled) {
      // Grab/move previews carry a vanish mask and are always drawn whole.
      const partialBrush = brush === 'inflate' || brush === 'smooth';
      if (partialBrush && !(perf.partial.partialRendersInStroke > 0)) throw new Error('no partial redraw happened during the check stroke');
      // Identical up to rasterizer noise: at most 0.05% of the pixels differ.
      if (perf.partial.differ > 0.0005 * perf.partial.pixels) {
        throw new Error(`the partially redrawn picture differs from a full redraw in ${perf.partial.differ} of ${perf.partial.pixels} pixels (max ${perf.partial.maxDiff})`);
      }
    }
    perf.sculpt = {
      triangles: mid, brush, frames: lat.length,
      positionsOnlyFrames: m.positionsOnlyFrames, sparseFrames: m.sparseFrames,
      // pointer event → picture drawn (GPU finished).
      latencyMsMedian: round(median(lat)), latencyMsP95: round(pct(lat, 0.95)),
      // Its parts (medians): waiting for the previous frame's answer, request
      // → frame received (of which the server's own `ms`), parse + apply +
      // normals, waiting for the animation frame, drawing (GPU finished).
      waitMsMedian: round(median(m.waitMs)), roundTripMsMedian: round(median(m.roundTripMs)),
      serverMsMedian: round(median(m.serverMs)), clientMsMedian: round(median(m.clientMs), 2),
      toRenderMsMedian: round(median(m.toRenderMs)), renderMsMedian: round(median(m.renderMs)),
      // Second stroke without waiting for the GPU (latency to draw calls issued).
      issuedLatencyMsMedian: round(median(q.strokeLatencies)), issuedLatencyMsP95: round(pct(q.strokeLatencies, 0.95)),
      issuedFrames: q.strokeLatencies.length,
      // Triangles drawn per stroke picture (partial redraws draw only those
      // meeting the changed rectangle).
      drawnTrianglesMedian: median(m.drawnTriangles),
    };
    perf.renderer = await page.evaluate(() => {
      const gl = document.querySelector('canvas').getContext('webgl2');
      const info = gl.getExtension('WEBGL_debug_renderer_info');
      return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
    });
    console.log(`  orbit: ${JSON.stringify(perf.orbit)}`);
    console.log(`  sculpt: ${JSON.stringify(perf.sculpt)}`);
    fs.writeFileSync(path.join(artifacts, 'perf.json'), JSON.stringify({ when: new Date().toISOString(), ...perf }, null, 2) + '\n');
    if (!lat.length) throw new Error('no stroke frame was measured');
  }],

  ['bunny: inflate dragged across the haunch with the mouse keeps one piece and its five holes', async (page) => {
    const file = path.join(meshesDir, 'stanford-bunny.obj');
    if (!fs.existsSync(file)) return 'SKIP';
    const v = await version(page);
    await page.setInputFiles(tid('import-input'), file);
    await waitVersionAbove(page, v, 60000);
    await setWorkspace(page, 'sculpt');
    // shared/data/meshes/README.md: 69,451 triangles, one piece, 5 holes.
    await waitStats(page, /components 1 · genus 0 · boundary loops 5/);
    await page.click(tid('tool-inflate'));
    await setRange(page, 'radius', 5);
    await setRange(page, 'strength', 1);
    await page.evaluate(() => window.__holey.setView([0, 0, 1]));
    await page.waitForTimeout(100);
    // Across the haunch, 40 small steps (the issue's stroke), seen from
    // the bunny's right side (+z): points just in front of the surface.
    const from = await page.evaluate((p) => window.__holey.project(p), [-0.01, 0.07, 0.07]);
    const to = await page.evaluate((p) => window.__holey.project(p), [0.04, 0.09, 0.07]);
    const PARTS = ['strokeLatencies', 'waitMs', 'roundTripMs', 'serverMs', 'clientMs', 'toRenderMs', 'renderMs'];
    await page.evaluate((keys) => {
      for (const k of keys) window.__holey[k].length = 0;
    }, PARTS);
    const before = await version(page);
    const counts = () => page.evaluate(() => ({ patch: window.__holey.patchFrames, preview: window.__holey.previewFrames, frames: window.__holey.frames }));
    const c0 = await counts();
    for (const sign of [1, -1]) {
      const [a, b] = sign > 0 ? [from, to] : [to, from];
      // Ctrl held as the button goes down deflates (the way back), as
      // the library test stanford_bunny_inflate_and_deflate_across_the_haunch.
      // The press must land on the surface: one that misses orbits (with
      // Ctrl: pans) the view and sends every later stroke elsewhere on
      // the bunny. The first stroke's end lies near the haunch's outline,
      // which its inflate moves: the way back starts at the first point of
      // its path the committed picture has surface under.
      await waitFor(page, 'the committed frame', () => window.__holey.frameVersion === window.__holey.version && !window.__holey.viewer.frame.preview);
      const at = (i) => [a[0] + ((b[0] - a[0]) * i) / 40, a[1] + ((b[1] - a[1]) * i) / 40];
      let start = 0;
      while (start < 10 && !(await page.evaluate(([x, y]) => !!window.__holey.viewer.pick(x, y), at(start)))) start++;
      await page.mouse.move(...at(start));
      if (sign < 0) await page.keyboard.down('Control');
      await page.mouse.down();
      await waitFor(page, 'the stroke to start (the press picked the surface)', () => window.__holey.stroking, undefined, 5000);
      for (let i = start + 1; i <= 40; i++) {
        await page.mouse.move(...at(i));
        await page.waitForTimeout(20);
      }
      await page.mouse.up();
      if (sign < 0) await page.keyboard.up('Control');
      await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
    }
    await waitVersionAbove(page, before, 60000);
    const signs = sentStrokes.map((x) => Math.sign(x.strength));
    if (signs.join() !== '1,-1') throw new Error(`the strokes' strengths have signs ${signs}: the way back with Ctrl must deflate`);
    await page.screenshot({ path: path.join(artifacts, '9-bunny-inflate.png') });
    await waitStats(page, /components 1 · genus 0 · boundary loops 5/);
    const got = await page.evaluate((keys) => Object.fromEntries(keys.map((k) => [k, [...window.__holey[k]]])), PARTS);
    const c1 = await counts();
    // Remeshing changes connectivity at most frames: those travel as
    // patches (PROTOCOL.md, bit 5). Mid-stroke, the picture built from
    // patches and partial redraws must equal a full redraw of that state.
    const p0 = await page.evaluate(() => window.__holey.partial);
    // With the wireframe on: patches carry the edges too.
    await page.click(tid('wireframe'));
    await page.mouse.move(from[0], from[1] + 20);
    await page.mouse.down();
    await waitFor(page, 'the check stroke to start (the press picked the surface)', () => window.__holey.stroking, undefined, 5000);
    for (let i = 1; i <= 25; i++) {
      await page.mouse.move(from[0] + ((to[0] - from[0]) * i) / 25, from[1] + 20 + ((to[1] - from[1]) * i) / 25);
      await page.waitForTimeout(20);
    }
    await waitFor(page, 'the stroke frames to be answered', () => {
      const s = window.__holey.strokeInfo;
      return s && !s.inflight && !s.queued;
    }, undefined, 60000);
    await page.waitForTimeout(100);
    const check = await page.evaluate(() => window.__holey.comparePartialToFull());
    await page.screenshot({ path: path.join(artifacts, '10-bunny-patch-check.png') });
    // The patched edge list is the set of the patched triangles' edges.
    check.edges = await page.evaluate(() => {
      const f = window.__holey.viewer.frame, t = f.tris, e = f.edges;
      const key = (a, b) => (a < b ? a * 4294967296 + b : b * 4294967296 + a);
      const want = new Set();
      for (let i = 0; i < t.length; i += 3) {
        want.add(key(t[i], t[i + 1])).add(key(t[i + 1], t[i + 2])).add(key(t[i + 2], t[i]));
      }
      const got = new Set();
      for (let i = 0; i < e.length; i += 2) got.add(key(e[i], e[i + 1]));
      return { ne: f.ne, distinct: got.size, fromTriangles: want.size, same: got.size === f.ne && got.size === want.size && [...got].every((k) => want.has(k)) };
    });
    const c2 = await counts();
    const v2 = await version(page);
    await page.evaluate(() => {
      const f = window.__holey.viewer.frame;
      window.__midStroke = { positions: Float32Array.from(f.positions), tris: Uint32Array.from(f.tris) };
    });
    await page.mouse.up();
    await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
    await waitVersionAbove(page, v2, 60000);
    await waitFor(page, 'the committed frame', () => window.__holey.frameVersion === window.__holey.version && !window.__holey.viewer.frame.preview);
    // An inflate commits its last frame's mesh. The commit is a commit
    // frame (PROTOCOL.md): the page keeps what its patches built. The
    // document's whole frame, asked for again (hello), must be exactly
    // that, edge slots included.
    check.commitFrame = await page.evaluate(() => {
      const f = window.__holey.viewer.frame;
      return !!f.sparse && f.sparseIdx.length === 0;
    });
    const framesBefore = await page.evaluate(() => {
      const f = window.__holey.viewer.frame;
      window.__committedShown = { positions: Float32Array.from(f.positions), tris: Uint32Array.from(f.tris), edges: Uint32Array.from(f.edges) };
      return window.__holey.frames;
    });
    await page.evaluate(() => window.__holey.request('hello'));
    await waitFor(page, 'the whole frame asked for', (n) => window.__holey.frames > n && !window.__holey.viewer.frame.positionsOnly, framesBefore);
    check.commitMatchesPatches = await page.evaluate(() => {
      const f = window.__holey.viewer.frame, m = window.__midStroke, c = window.__committedShown;
      const same = (a, b) => a.length === b.length && a.every((x, i) => x === b[i]);
      return same(m.positions, c.positions) && same(m.tris, c.tris)
        && same(c.positions, f.positions) && same(c.tris, f.tris) && same(c.edges, f.edges);
    });
    await page.click(tid('wireframe'));
    check.partialRendersInStroke = check.partialRenders - p0.renders;
    check.patchFrames = c2.patch - c1.patch;
    console.log(`  bunny patch check: ${JSON.stringify(check)}`);
    if (!(c1.patch - c0.patch > 0) || !(check.patchFrames > 0)) throw new Error(`no patch frame during the remeshing strokes: ${JSON.stringify({ c0, c1, c2 })}`);
    if (!check.commitFrame) throw new Error('the stroke was committed with a whole frame, not a commit frame');
    if (!check.commitMatchesPatches) throw new Error('the document\'s whole frame differs from the mesh the patches built');
    if (!check.edges.same) throw new Error(`the patched edges are not the patched triangles' edges: ${JSON.stringify(check.edges)}`);
    if (p0.enabled) {
      if (!(check.partialRendersInStroke > 0)) throw new Error('no partial redraw during the bunny check stroke');
      if (check.differ > 0.0005 * check.pixels) {
        throw new Error(`the picture built from patches differs from a full redraw in ${check.differ} of ${check.pixels} pixels (max ${check.maxDiff})`);
      }
    }
    await waitStats(page, /components 1 · genus 0 · boundary loops 5/);
    const ms = got.serverMs;
    const lat = got.strokeLatencies;
    // Server time per frame, and pointer event to picture (issue 15's
    // 33 ms target on the bunny; the drawing is not waited for here) with
    // its parts' medians, as scenario 9 reports them.
    perf.bunnyInflate = {
      frames: ms.length, serverMsMedian: round(median(ms)), serverMsP95: round(pct(ms, 0.95)),
      latencyMsMedian: round(median(lat)), latencyMsP95: round(pct(lat, 0.95)), latencyFrames: lat.length,
      waitMsMedian: round(median(got.waitMs)), roundTripMsMedian: round(median(got.roundTripMs)),
      clientMsMedian: round(median(got.clientMs)), toRenderMsMedian: round(median(got.toRenderMs)),
      renderMsMedian: round(median(got.renderMs)),
      // Frames of the two strokes, and of them connectivity patches.
      previewFrames: c1.preview - c0.preview, patchFrames: c1.patch - c0.patch,
    };
    console.log(`  bunny inflate: ${JSON.stringify(perf.bunnyInflate)}`);
    const perfFile = path.join(artifacts, 'perf.json');
    const saved = fs.existsSync(perfFile) ? JSON.parse(fs.readFileSync(perfFile, 'utf8')) : {};
    fs.writeFileSync(perfFile, JSON.stringify({ ...saved, bunnyInflate: perf.bunnyInflate }, null, 2) + '\n');
    if (!ms.length) throw new Error('no stroke frame was answered');
  }],

  ['bunny: snake-hook the long ear\'s tip over into the crown with the mouse: one piece, five holes, genus 1 (the handle)', async (page) => {
    if (!fs.existsSync(path.join(meshesDir, 'stanford-bunny.obj'))) return 'SKIP';
    await waitStats(page, /boundary loops 5/);
    await page.click(tid('tool-snake-hook'));
    await setRange(page, 'radius', 5);
    // The path of crates/sculpt/tests/real_meshes.rs: the ear's tip (the
    // highest point), up and forward, above the crown (clear of the other
    // ear), into the head.
    const tip = [-0.017522, 0.187321, -0.019849];
    const crown = [-0.065, 0.1564, 0.02];
    const knots = [tip, [-0.04, tip[1] + 0.013, 0.02], [crown[0], crown[1] + 0.025, crown[2] + 0.005], [crown[0], crown[1] - 0.02, crown[2]]];
    const corners = [tip];
    for (let k = 1; k < knots.length; k++) {
      for (let i = 1; i <= 10; i++) corners.push(knots[k].map((x, j) => knots[k - 1][j] + ((x - knots[k - 1][j]) * i) / 10));
    }
    // The hook follows the pointer in the view plane through the pick:
    // look along the normal of the plane through the tip and the last two
    // knots, so that the path lies in it.
    const sub = (a, b) => a.map((x, i) => x - b[i]);
    const [u, w] = [sub(knots[2], tip), sub(knots[3], tip)];
    const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
    await page.evaluate((d) => window.__holey.setView(d), n[2] > 0 ? n : n.map((x) => -x));
    await page.waitForTimeout(100);
    const screen = [];
    for (const c of corners) screen.push(await page.evaluate((p) => window.__holey.project(p), c));
    const v = await version(page);
    await page.mouse.move(screen[0][0], screen[0][1]);
    await page.mouse.down();
    for (let k = 1; k < screen.length; k++) {
      await page.mouse.move(screen[k][0], screen[k][1]);
      await page.waitForTimeout(25);
    }
    await waitFor(page, 'the stroke frames to be answered', () => {
      const s = window.__holey.strokeInfo;
      return s && !s.inflight && !s.queued;
    }, null, 60000);
    await page.mouse.up();
    await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
    await waitVersionAbove(page, v, 60000);
    await page.screenshot({ path: path.join(artifacts, '11-bunny-ear-snake-hook.png') });
    console.log(`  after the hook: ${await statsText(page)}`);
    // With the mouse the dabs fall where the pointer events do, and a long
    // step can crumple the tentacle's tip through itself; the engine trims
    // it without changing the topology, and the hook holds on (it lets go
    // only where the Euler characteristic changes: the library test
    // stanford_bunny_ear_hooked_with_the_mouse_holds_on_past_a_trimmed_tip
    // replays a run that let go there). The bunny stays one piece with its
    // five holes and gains the handle, nothing non-manifold.
    await waitStats(page, /components 1 · genus 1 · boundary loops 5/);
    const text = await statsText(page);
    if (/non-manifold/.test(text)) throw new Error(`the ear left a non-manifold mesh: ${text}`);
  }],

  ['teapot: Weld closes its patch seams and Make manifold lets the model tools take it', async (page) => {
    const file = path.join(meshesDir, 'teapot.obj');
    if (!fs.existsSync(file)) return 'SKIP';
    const v = await version(page);
    await page.setInputFiles(tid('import-input'), file);
    await waitVersionAbove(page, v, 60000);
    // Not a 2-manifold: it opens in the sculpt workspace, with its seams
    // open (shared/data/meshes/README.md: 10 loops, 4 pieces).
    await waitFor(page, 'the sculpt workspace', () => window.__holey.state?.workspace === 'sculpt');
    await waitStats(page, /components 4 · .* · boundary loops 10/);
    await page.fill(tid('weld-distance'), '0.01');
    await clickForNewVersion(page, 'op-weld');
    // Welded: 3 pieces, 6 loops (the README's measurement).
    await waitStats(page, /components 3 · .* · boundary loops 6/);
    // The model tools refuse it until it is made a 2-manifold.
    await page.click(tid('workspace-model'));
    await waitFor(page, 'an error toast naming the button', () =>
      [...document.querySelectorAll('[data-testid="toast-error"]')].some((t) => /Make manifold/.test(t.textContent)));
    const toasts = await page.$$eval('[data-testid="toasts"] > *', (els) => els.length);
    if (toasts !== 1) throw new Error(`${toasts} toasts on screen; one at a time`);
    await clickForNewVersion(page, 'op-make-manifold');
    await setWorkspace(page, 'model');
    await page.screenshot({ path: path.join(artifacts, '12-teapot-repaired.png') });
  }],

  ['a second tab shares the session: each sees the other\'s changes', async (page, url) => {
    const other = await page.context().browser().newPage({ viewport: { width: 1280, height: 800 } });
    try {
      other.on('pageerror', (e) => consoleErrors.push(`second tab: ${e.message}`));
      await other.goto(url);
      await other.waitForFunction(() => window.__holey?.frames > 0, null, { timeout: 30000 });
      await other.waitForFunction(() => document.querySelectorAll('[data-testid="primitive-select"] option').length > 0, null, { timeout: 10000 });
      await setWorkspace(page, 'model');
      await createPrimitive(page, '@torus');
      await waitStats(page, genusRe(1));
      await waitStats(other, genusRe(1));
      await createPrimitive(other, '@cube');
      await waitStats(other, genusRe(0));
      await waitStats(page, genusRe(0));
      // Undo in the first tab undoes the second tab's change for both.
      await page.click(tid('undo'));
      await waitStats(page, genusRe(1));
      await waitStats(other, genusRe(1));
      await other.screenshot({ path: path.join(artifacts, '9-second-tab.png') });
    } finally {
      await other.close();
    }
  }],

  // ---- TopMod's toolbox (issue 18) ----------------------------------------------
  // Expected counts are worked out here from each operation's definition
  // and the counts the stats bar showed before it, never read from a result.

  ['Remesh panel: every scheme listed; dual and corner cutting of a cube; undo restores it', async (page) => {
    if (useMock) return 'SKIP'; // the mock server has no remeshing
    const cube = await modelOf(page, '@cube', /\bV 8 · E 12 · F 6\b/);
    const C = 2 * cube.E; // corners of a closed mesh
    // The panel offers what the server lists, the issue's schemes among them.
    const offered = await page.$$eval(`${tid('remesh-scheme')} option`, (os) => os.map((o) => o.value));
    const listed = await page.evaluate(() => window.__holey.request('remesh_schemes').then((r) => r.schemes.map((x) => x.name)));
    if (JSON.stringify(offered) !== JSON.stringify(listed)) throw new Error(`the panel offers ${offered.join(' ')}; the server lists ${listed.join(' ')}`);
    for (const name of ['dual', 'sqrt3', 'triangulate', 'loop', 'root4', 'linear-vertex-insertion', 'vertex-truncation',
      'dual-vertex-truncation', 'stellate', 'double-stellate', 'corner-cutting', 'modified-corner-cutting', 'simplest',
      'honeycomb', '12.6.4', 'dual-12.6.4', 'pentagonalization', 'dual-pentagonalization', 'checkerboard',
      'dual-checkerboard', 'global-extrude', 'dual-global-extrude', 'dome', 'fractal']) {
      if (!offered.includes(name)) throw new Error(`the Remesh panel lacks ${name}`);
    }
    const apply = async (scheme, want, params = {}) => {
      await page.selectOption(tid('remesh-scheme'), scheme);
      for (const [name, value] of Object.entries(params)) await page.fill(tid(`remesh-param-${name}`), String(value));
      await clickForNewVersion(page, 'op-remesh');
      await waitStats(page, new RegExp(`\\bV ${want[0]} · E ${want[1]} · F ${want[2]}\\b.*genus 0(?!\\d)`));
    };
    const undo = async () => {
      await clickForNewVersion(page, 'undo');
      await waitStats(page, /\bV 8 · E 12 · F 6\b/);
    };
    // Dual: a vertex per face, a face per vertex, an edge across each edge.
    await apply('dual', [cube.F, cube.E, cube.V]);
    await page.screenshot({ path: path.join(artifacts, '14-remesh-dual.png') });
    await undo();
    // Corner cutting has a tension α: its input shows TopMod's 9/16.
    await page.selectOption(tid('remesh-scheme'), 'corner-cutting');
    const alpha = Number(await page.inputValue(tid('remesh-param-corner_cutting_alpha')));
    if (Math.abs(alpha - 9 / 16) > 1e-12) throw new Error(`corner cutting's α shows ${alpha}, not 9/16`);
    // Doo–Sabin's connectivity: a vertex per corner, two edges per corner,
    // a face per face, edge and vertex.
    await apply('corner-cutting', [C, 2 * C, cube.F + cube.E + cube.V], { corner_cutting_alpha: 0.7 });
    await page.screenshot({ path: path.join(artifacts, '14-remesh-corner-cutting.png') });
    await undo();
    // Vertex truncation: every corner cut off (2E, E + C, F + V).
    await apply('vertex-truncation', [2 * cube.E, cube.E + C, cube.F + cube.V]);
    await undo();
    // The dual is not defined with a boundary: the page says why.
    await createPrimitive(page, '@plane');
    await page.selectOption(tid('remesh-scheme'), 'dual');
    const note = await page.textContent(tid('remesh-note'));
    if (!/closed/.test(note)) throw new Error(`the dual's note says "${note}", not that it needs a closed surface`);
    await page.click(tid('op-remesh'));
    await waitFor(page, 'an error toast about the boundary', () =>
      [...document.querySelectorAll('[data-testid="toast-error"]')].some((t) => /boundary/.test(t.textContent)));
  }],

  ['Extrude a selected face twice, then undo both', async (page) => {
    if (useMock) return 'SKIP';
    const cube = await modelOf(page, '@cube', /\bV 8 · E 12 · F 6\b/);
    // Click the middle of the +z side.
    await pickFaceAt(page, [0.3, 0.4, 1], [0, 0, 1]);
    await page.selectOption(tid('extrude-kind'), 'plain');
    await page.fill(tid('extrude-distance'), '0.8');
    await page.fill(tid('extrude-scale'), '0.7');
    await page.fill(tid('extrude-rotation'), '15');
    await page.fill(tid('extrude-count'), '1');
    // One plain extrusion of a d-gon adds d vertices, 2d edges, d faces.
    const d = 4;
    await clickForNewVersion(page, 'op-extrude');
    await waitStats(page, new RegExp(`\\bV ${cube.V + d} · E ${cube.E + 2 * d} · F ${cube.F + d}\\b.*genus 0(?!\\d)`));
    // The new top is selected, on the new version: extrude it again.
    await waitFor(page, 'the new top selected', () => {
      const s = window.__holey.selection;
      return s.faces.length === 1 && s.version === window.__holey.version;
    });
    await clickForNewVersion(page, 'op-extrude');
    await waitStats(page, new RegExp(`\\bV ${cube.V + 2 * d} · E ${cube.E + 4 * d} · F ${cube.F + 2 * d}\\b`));
    await page.evaluate(() => window.__holey.setView([0.3, 0.4, 1]));
    await page.waitForTimeout(200);
    await page.screenshot({ path: path.join(artifacts, '15-extrude.png') });
    for (let i = 0; i < 2; i++) {
      await clickForNewVersion(page, 'undo');
    }
    await waitStats(page, /\bV 8 · E 12 · F 6\b/);
    // Nothing selected: the page says so instead of sending a request.
    await page.click(tid('op-extrude'));
    await waitFor(page, 'an error toast asking for faces', () =>
      [...document.querySelectorAll('[data-testid="toast-error"]')].some((t) => /Select the faces/.test(t.textContent)));
  }],

  ['Wireframe and columns of a cube: genus E − V + 1', async (page) => {
    if (useMock) return 'SKIP';
    const { V, E } = await modelOf(page, '@cube', /\bV 8 · E 12 · F 6\b/);
    await page.fill(tid('wireframe-thickness'), '0.25');
    await clickForNewVersion(page, 'op-wireframe');
    // TopMod's wireframe: two vertices per corner (4E), ten edges per edge,
    // 4E + 2V faces; a tube per edge gives genus E − V + 1.
    await waitStats(page, new RegExp(`\\bV ${4 * E} · E ${10 * E} · F ${4 * E + 2 * V}\\b.*genus ${E - V + 1}(?!\\d)`));
    await page.evaluate(() => window.__holey.setView());
    await page.waitForTimeout(200);
    await page.screenshot({ path: path.join(artifacts, '16-wireframe.png') });
    await clickForNewVersion(page, 'undo');
    await page.fill(tid('columns-sides'), '6');
    await clickForNewVersion(page, 'op-columns');
    // Columns of n sides: 2nE vertices, the same genus.
    await waitStats(page, new RegExp(`\\bV ${2 * 6 * E} · .*genus ${E - V + 1}(?!\\d)`));
    await page.screenshot({ path: path.join(artifacts, '16-columns.png') });
  }],

  ['Cut a selected corner of a cube, then undo', async (page) => {
    if (useMock) return 'SKIP';
    const { V, E, F } = await modelOf(page, '@cube', /\bV 8 · E 12 · F 6\b/);
    await page.evaluate(() => window.__holey.setView([1, 0.8, 1.2]));
    await page.waitForTimeout(100);
    // Shift-click on the +z side just inside its (1, 1, 1) corner picks
    // that corner (Shift picks corners in any mode).
    const at = await page.evaluate(() => window.__holey.project([0.9, 0.9, 1]));
    await page.keyboard.down('Shift');
    await page.mouse.click(at[0], at[1]);
    await page.keyboard.up('Shift');
    await waitFor(page, 'one selected corner', () => window.__holey.selection.corners.length === 1);
    await page.fill(tid('cut-distance'), '0.5');
    await clickForNewVersion(page, 'op-cut');
    // A vertex of valence k becomes a k-gon: +(k − 1) vertices, +k edges,
    // +1 face; a cube's corners have valence 3.
    const k = 3;
    await waitStats(page, new RegExp(`\\bV ${V + k - 1} · E ${E + k} · F ${F + 1}\\b`));
    await waitFor(page, 'the new triangle selected', () => window.__holey.selection.faces.length === 1);
    await page.screenshot({ path: path.join(artifacts, '17-cut-corner.png') });
    await clickForNewVersion(page, 'undo');
    await waitStats(page, /\bV 8 · E 12 · F 6\b/);
  }],

  ['Truncate every vertex of an icosahedron by a third: the soccer ball', async (page) => {
    if (useMock) return 'SKIP';
    const { V, E, F } = await modelOf(page, '@icosahedron', /\bV 12 · E 30 · F 20\b/);
    await page.fill(tid('truncate-fraction'), String(1 / 3));
    await clickForNewVersion(page, 'op-truncate-all');
    // Every vertex becomes a face: 2E vertices, 3E edges, F + V faces.
    await waitStats(page, new RegExp(`\\bV ${2 * E} · E ${3 * E} · F ${F + V}\\b`));
    // The twelve new pentagons are the selection.
    await waitFor(page, 'the new faces selected', () => window.__holey.selection.faces.length === 12);
    await page.screenshot({ path: path.join(artifacts, '18-truncate-soccer-ball.png') });
  }],

  ['Selection tools on @cube:2: face loop, grow, shrink, invert, edge ring', async (page) => {
    if (useMock) return 'SKIP';
    await setWorkspace(page, 'model');
    const v0 = await version(page);
    await page.evaluate(() => window.__holey.request('primitive', { spec: '@cube:2' }));
    await waitVersionAbove(page, v0);
    await waitStats(page, /\bF 24\b/);
    // A quad of the +z side, away from the side's middle vertex.
    const at = await pickFaceAt(page, [0.3, 0.4, 1], [0.5, 0.5, 1]);
    const seed = await page.evaluate(() => window.__holey.selection.faces[0]);
    const sel = () => page.evaluate(() => ({ faces: [...window.__holey.selection.faces], edges: [...window.__holey.selection.edges] }));
    const run = async (id, what, check) => {
      await page.click(tid(id));
      await waitFor(page, what, check);
    };
    // A 2×2-per-side cube: a face loop runs once around, 4 sides × 2 quads.
    await run('sel-face-loop', 'a loop of 8 faces', () => window.__holey.selection.faces.length === 8);
    await page.screenshot({ path: path.join(artifacts, '19-face-loop.png') });
    // Grow adds the faces sharing a vertex with the seed, a corner quad of
    // the +z side: the other 3 quads of its side (all meet at the side's
    // middle vertex) and, across its two outer edges, 2 quads of the +x
    // side and 2 of the +y side (the corner vertex adds none more):
    // 1 + 3 + 2 + 2 = 8.
    await page.evaluate((f) => { window.__holey.selection.faces.splice(0, Infinity, f); }, seed);
    await run('sel-grow', 'a grown selection of 8 faces', () => window.__holey.selection.faces.length === 8);
    const grown = (await sel()).faces;
    if (!grown.includes(seed)) throw new Error(`grow dropped the seed ${seed}: ${grown}`);
    await run('sel-shrink', 'the seed back', () => window.__holey.selection.faces.length === 1);
    const back = (await sel()).faces;
    if (back[0] !== seed) throw new Error(`shrink of grow gave ${back}, not ${seed}`);
    await run('sel-invert', 'the other 23 faces', () => window.__holey.selection.faces.length === 23);
    // An edge ring around the cube: 8 edges.
    await page.check('[name=pick][value=edge]');
    await page.keyboard.press('Escape');
    await waitFor(page, 'nothing selected', () => !window.__holey.selection.faces.length);
    await page.mouse.click(at[0], at[1]);
    await waitFor(page, 'one selected edge', () => window.__holey.selection.edges.length === 1);
    await run('sel-edge-ring', 'a ring of 8 edges', () => window.__holey.selection.edges.length === 8);
    await page.screenshot({ path: path.join(artifacts, '19-edge-ring.png') });
  }],
  // ---- the sculpt workspace (issue 19) ------------------------------------------
  // Oracles: positions read back from the page's frames (the server's mesh
  // to f32), the fields the page sent, and counts worked out here.

  ['sculpt: every new brush button strokes @sphere and moves it; falloff and strength are sent', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    await setRange(page, 'radius', 20);
    await setRange(page, 'strength', 1);
    const before = await positions(page);
    const radius = await page.evaluate(() => window.__holey.bbox.diag * 0.2);
    const falloffs = ['sphere', 'root', 'sharp', 'linear', 'constant', 'smooth', 'custom', 'sphere'];
    const expected = { draw: 0.05 * radius, clay: 0.05 * radius, crease: 0.1 * radius, flatten: 1, pinch: 0.25, scrape: 1, scale: 0.1, layer: 0.25 * radius };
    for (const [i, brush] of Object.keys(expected).entries()) {
      await page.click(tid(`tool-${brush}`));
      await setRange(page, 'strength', 1); // each brush has its own
      if (!(await page.$eval(tid(`tool-${brush}`), (b) => b.classList.contains('active')))) throw new Error(`${brush}'s button is not shown active`);
      await page.selectOption(tid('falloff-select'), falloffs[i]);
      const v = await version(page);
      await dragThrough(page, [-0.3, 0.1, 0.95], [0.3, -0.1, 0.95]);
      await waitVersionAbove(page, v);
      const after = await positions(page);
      const moved = movedVertices(before, after);
      // The brush reaches 0.69 from the path: nothing on the back moves.
      const far = moved.filter((k) => before[3 * k + 2] < -0.5);
      if (moved.length < 5 || far.length) throw new Error(`${brush}: ${moved.length} vertices moved, ${far.length} of them on the far side`);
      const sent = await page.evaluate(() => window.__holey.strokesSent.at(-1));
      if (sent.brush !== brush) throw new Error(`sent brush ${sent.brush}, not ${brush}`);
      const f = falloffs[i];
      if (f === 'custom' ? JSON.stringify(sent.falloff) !== JSON.stringify({ custom: [1, 0.8, 0.5, 0.2, 0] }) : sent.falloff !== f) {
        throw new Error(`${brush}: sent falloff ${JSON.stringify(sent.falloff)}, not ${f}`);
      }
      if (Math.abs(sent.strength - expected[brush]) > 1e-9) throw new Error(`${brush}: sent strength ${sent.strength}, not ${expected[brush]}`);
      if (i === 0) await page.screenshot({ path: path.join(artifacts, '20-draw.png') });
      await clickForNewVersion(page, 'undo');
    }
    // Ctrl inverts draw: a negative strength, and what moved went inwards.
    await page.click(tid('tool-draw'));
    const v = await version(page);
    await dragThrough(page, [-0.3, 0.1, 0.95], [0.3, -0.1, 0.95], { modifiers: ['Control'] });
    await waitVersionAbove(page, v);
    const sent = await page.evaluate(() => window.__holey.strokesSent.at(-1));
    if (!(sent.strength < 0)) throw new Error(`Ctrl-draw sent strength ${sent.strength}`);
    const after = await positions(page);
    const out = movedVertices(before, after).filter((k) => norm(after, k) > norm(before, k));
    if (out.length) throw new Error(`Ctrl-draw pushed ${out.length} vertices outwards`);
    await page.screenshot({ path: path.join(artifacts, '20-draw-carved.png') });
    // A drag brush has no strength: its slider is disabled.
    await page.click(tid('tool-grab'));
    if (!(await page.$eval(tid('strength'), (s) => s.disabled))) throw new Error('grab leaves the strength slider enabled');
    await page.click(tid('tool-draw'));
    if (await page.$eval(tid('strength'), (s) => s.disabled)) throw new Error('draw leaves the strength slider disabled');
    await page.selectOption(tid('falloff-select'), 'smooth');
  }],

  ['sculpt: a mouse stroke with symmetry X on one side of @sphere changes both sides alike', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    await page.click(tid('tool-draw'));
    await setRange(page, 'radius', 12);
    await setRange(page, 'strength', 1);
    await page.check(tid('symmetry-x'));
    await page.selectOption(tid('symmetry-about'), 'origin');
    const before = await positions(page);
    const v = await version(page);
    // Entirely on the +x side.
    await dragThrough(page, [0.5, 0.3, 0.81], [0.6, -0.2, 0.77]);
    await waitVersionAbove(page, v);
    await page.screenshot({ path: path.join(artifacts, '21-symmetry-x.png') });
    await page.uncheck(tid('symmetry-x'));
    const sent = await page.evaluate(() => window.__holey.strokesSent.at(-1));
    if (sent.symmetry !== 'x' || sent.symmetry_about !== 'origin') throw new Error(`sent ${JSON.stringify(sent)}`);
    const after = await positions(page);
    const moved = movedVertices(before, after);
    const plus = moved.filter((k) => before[3 * k] > 0.2).length, minus = moved.filter((k) => before[3 * k] < -0.2).length;
    if (plus < 5 || plus !== minus) throw new Error(`moved ${plus} vertices on the +x side and ${minus} on the −x side`);
    // Every vertex has its mirror image across x = 0 (f32 rounding apart).
    const worst = mirrorDistance(after);
    if (worst > 1e-5) throw new Error(`a vertex is ${worst} from the nearest mirror of another`);
  }],

  ['sculpt: [ and ] change the radius, Shift+[ and ] the strength; each brush keeps its own strength; F sizes the radius on screen', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    await setRange(page, 'radius', 10);
    await setRange(page, 'strength', 0.5);
    await page.locator(tid('canvas')).focus();
    const radius = () => page.$eval(tid('radius'), (r) => Number(r.value));
    const strength = () => page.$eval(tid('strength'), (r) => Number(r.value));
    await page.keyboard.press(']');
    const up = await radius();
    if (!(up > 10)) throw new Error(`] left the radius at ${up}`);
    await page.keyboard.press('[');
    const down = await radius();
    if (!(down < up)) throw new Error(`[ left the radius at ${down}`);
    await page.keyboard.press('Shift+BracketRight');
    if (Math.abs((await strength()) - 0.55) > 1e-9) throw new Error(`Shift+] made the strength ${await strength()}`);
    await page.keyboard.press('Shift+BracketLeft');
    if (Math.abs((await strength()) - 0.5) > 1e-9) throw new Error(`Shift+[ made the strength ${await strength()}`);
    // Each brush keeps its own strength (Blender, SculptGL); the radius is shared.
    await page.click(tid('tool-draw'));
    await setRange(page, 'strength', 0.8);
    await page.click(tid('tool-smooth'));
    await setRange(page, 'strength', 0.3);
    await page.click(tid('tool-draw'));
    if (Math.abs((await strength()) - 0.8) > 1e-9) throw new Error(`draw came back at strength ${await strength()}, not its 0.8`);
    if ((await page.textContent(tid('strength-value'))) !== '0.80') throw new Error(`the strength label says ${await page.textContent(tid('strength-value'))}`);
    if ((await radius()) !== down) throw new Error(`choosing a brush changed the radius to ${await radius()}`);
    await page.keyboard.press('2');
    if (Math.abs((await strength()) - 0.3) > 1e-9) throw new Error(`smooth came back at strength ${await strength()}, not its 0.3`);
    // Shift-drag smooths with smooth's own strength while draw is chosen.
    await page.click(tid('tool-draw'));
    await page.locator(tid('canvas')).focus();
    const sv = await version(page);
    await dragThrough(page, [-0.2, 0, 0.98], [0.2, 0, 0.98], { modifiers: ['Shift'] });
    await waitVersionAbove(page, sv);
    const shifted = await page.evaluate(() => window.__holey.strokesSent.at(-1));
    if (shifted.brush !== 'smooth' || Math.abs(shifted.strength - 0.3) > 1e-9) throw new Error(`Shift-drag sent ${JSON.stringify(shifted)}, not smooth at 0.3`);
    await setRange(page, 'strength', 0.5);
    await page.click(tid('tool-smooth'));
    await setRange(page, 'strength', 0.5);
    const radiusText = await page.textContent(tid('radius-value'));
    if (!radiusText.startsWith(`${down}%`)) throw new Error(`the radius label says ${radiusText}, the slider ${down}`);
    // F: the ring keeps its size with the pointer on its rim; moving the
    // pointer 60 px away from the ring's centre adds 60 px of radius.
    await setRange(page, 'radius', 10);
    const at = await page.evaluate(() => window.__holey.project([0, 0, 1]));
    const ppu = await page.evaluate(() => {
      const a = window.__holey.project([0, 0, 1]), b = window.__holey.project([0.01, 0, 1]);
      return Math.hypot(b[0] - a[0], b[1] - a[1]) / 0.01;
    });
    const diag = await page.evaluate(() => window.__holey.bbox.diag);
    await page.mouse.move(at[0], at[1]);
    await page.keyboard.press('f');
    await waitFor(page, 'F to start sizing the radius', () => window.__holey.sizing === 'radius');
    if (Math.abs((await radius()) - 10) > 0.5) throw new Error(`F alone changed the radius to ${await radius()}`);
    await page.mouse.move(at[0] + 60, at[1]);
    const want = 10 + (60 / ppu / diag) * 100;
    const got = await radius();
    if (Math.abs(got - want) > 0.51) throw new Error(`after 60 px the radius is ${got}%, not ${want.toFixed(2)}%`);
    await page.screenshot({ path: path.join(artifacts, '22-f-sizing.png') });
    await page.mouse.down();
    await page.mouse.up();
    await waitFor(page, 'the click to end the sizing', () => window.__holey.sizing === null);
    if ((await radius()) !== got) throw new Error('the click did not keep the new radius');
    if (await page.evaluate(() => window.__holey.stroking)) throw new Error('the click started a stroke');
    // Escape puts it back.
    await page.keyboard.press('f');
    await page.mouse.move(at[0] + 150, at[1] + 20);
    await page.keyboard.press('Escape');
    if ((await radius()) !== got) throw new Error(`Escape left the radius at ${await radius()}, not ${got}`);
  }],

  ['sculpt: mask paint, then a draw stroke over it leaves the masked vertices where they were; invert and clear', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    const nv = await page.evaluate(() => window.__holey.stats.vertices);
    await setRange(page, 'radius', 8);
    await page.click(tid('mask-paint'));
    const replies = await page.evaluate(() => window.__holey.maskReplies.length);
    await dragThrough(page, [-0.25, 0.05, 0.967], [0.25, 0.05, 0.967]);
    await waitFor(page, 'the mask from the server', (n) => window.__holey.maskReplies.length > n, replies);
    const painted = await page.evaluate(() => window.__holey.maskPaints.at(-1));
    const before = await positions(page);
    const mask = await page.evaluate(() => window.__holey.sculptMask);
    if (!mask) throw new Error('no mask came with the frame');
    // The oracle: every vertex within the radius of a dab, and no other.
    const r2 = painted.radius ** 2;
    for (let k = 0; k < nv; k++) {
      const inside = painted.points.some((c) => (before[3 * k] - c[0]) ** 2 + (before[3 * k + 1] - c[1]) ** 2 + (before[3 * k + 2] - c[2]) ** 2 <= r2 * (1 - 1e-6));
      const outside = painted.points.every((c) => (before[3 * k] - c[0]) ** 2 + (before[3 * k + 1] - c[1]) ** 2 + (before[3 * k + 2] - c[2]) ** 2 > r2 * (1 + 1e-6));
      if ((inside && !mask[k]) || (outside && mask[k])) throw new Error(`vertex ${k} is ${mask[k] ? '' : 'not '}masked`);
    }
    const n = mask.filter((m) => m).length;
    const reply = await page.evaluate(() => window.__holey.maskReplies.at(-1));
    if (n < 5 || reply !== n) throw new Error(`${n} vertices masked in the frame, the server said ${reply}`);
    await page.waitForTimeout(100);
    await page.screenshot({ path: path.join(artifacts, '23-mask.png') });
    // A wide draw stroke over the masked band.
    await page.click(tid('tool-draw'));
    await setRange(page, 'radius', 25);
    await setRange(page, 'strength', 1);
    const v = await version(page);
    await dragThrough(page, [-0.3, -0.1, 0.95], [0.3, 0.15, 0.94]);
    await waitVersionAbove(page, v);
    const after = await positions(page);
    let unmovedMasked = 0;
    for (let k = 0; k < nv; k++) {
      if (!mask[k]) continue;
      for (let c = 0; c < 3; c++) if (after[3 * k + c] !== before[3 * k + c]) throw new Error(`masked vertex ${k} moved`);
      unmovedMasked++;
    }
    const moved = movedVertices(before, after);
    if (moved.length < 10) throw new Error(`only ${moved.length} unmasked vertices moved`);
    await page.screenshot({ path: path.join(artifacts, '23-mask-then-draw.png') });
    const stillMasked = await page.evaluate(() => window.__holey.maskedCount);
    if (stillMasked !== n) throw new Error(`${stillMasked} vertices masked after the stroke, not ${n}`);
    await page.click(tid('mask-invert'));
    await waitFor(page, 'the inverted mask', (m) => window.__holey.maskedCount === m, nv - n);
    await page.click(tid('mask-clear'));
    await waitFor(page, 'no mask', () => window.__holey.maskedCount === 0 && window.__holey.sculptMask === null);
    const text = await page.textContent(tid('mask-count'));
    if (text) throw new Error(`the mask count still says "${text}"`);
  }],

  ['display: matcaps, orthographic view, front/side/top views and numpad keys, a PNG screenshot', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    const options = await page.$$eval(`${tid('matcap-select')} option`, (os) => os.map((o) => o.value));
    const matcaps = options.filter((o) => o !== 'studio');
    if (matcaps.length < 4) throw new Error(`only ${matcaps.length} matcaps offered: ${options}`);
    const centre = await page.evaluate(() => window.__holey.project([0, 0, 1]));
    const clip = { x: centre[0] - 40, y: centre[1] - 40, width: 80, height: 80 };
    const seen = new Set();
    for (const m of options) {
      await page.selectOption(tid('matcap-select'), m);
      await waitFor(page, `the ${m} material`, (x) => window.__holey.camera.material === x, m);
      await page.waitForTimeout(80);
      seen.add((await page.screenshot({ clip })).toString('base64'));
      if (m === 'studio' || m === 'clay' || m === 'chrome') await page.screenshot({ path: path.join(artifacts, `24-matcap-${m}.png`) });
    }
    if (seen.size !== options.length) throw new Error(`${options.length} materials drew ${seen.size} different pictures`);
    await page.selectOption(tid('matcap-select'), 'clay');
    const dir = () => page.evaluate(() => {
      const c = window.__holey.camera;
      const d = c.position.map((x, i) => x - c.target[i]);
      const l = Math.hypot(...d);
      return d.map((x) => Math.round((x / l) * 1000) / 1000);
    });
    const expectDir = async (what, want) => {
      const d = await dir();
      if (d.some((x, i) => Math.abs(x - want[i]) > 1e-3)) throw new Error(`${what}: the camera looks from ${d}, not ${want}`);
    };
    await page.click(tid('view-side'));
    await expectDir('Side', [1, 0, 0]);
    await page.click(tid('view-top'));
    await expectDir('Top', [0, 1, 0]);
    await page.click(tid('view-front'));
    await expectDir('Front', [0, 0, 1]);
    await page.locator(tid('canvas')).focus();
    await page.keyboard.press('Numpad3');
    await expectDir('numpad 3', [1, 0, 0]);
    await page.keyboard.press('Control+Numpad1');
    await expectDir('Ctrl+numpad 1', [0, 0, -1]);
    await page.keyboard.press('Numpad7');
    await expectDir('numpad 7', [0, 1, 0]);
    await page.keyboard.press('Numpad1');
    await expectDir('numpad 1', [0, 0, 1]);
    // Orthographic: the button and numpad 5; the sphere keeps its size.
    const size = () => page.evaluate(() => {
      const a = window.__holey.project([-1, 0, 0]), b = window.__holey.project([1, 0, 0]);
      return b[0] - a[0];
    });
    const perspective = await size();
    await page.check(tid('ortho-toggle'));
    await waitFor(page, 'the orthographic camera', () => window.__holey.camera.ortho);
    const ortho = await size();
    if (Math.abs(ortho - perspective) / perspective > 0.15) throw new Error(`the sphere is ${ortho} px wide in ortho, ${perspective} px in perspective`);
    await page.click(tid('view-side'));
    await expectDir('Side (ortho)', [1, 0, 0]);
    await page.click(tid('view-front'));
    await page.waitForTimeout(100);
    await page.screenshot({ path: path.join(artifacts, '24-ortho-front.png') });
    // A stroke picks right in the orthographic view too.
    await page.click(tid('tool-draw'));
    const v = await version(page);
    await dragThrough(page, [-0.2, 0, 0.98], [0.2, 0, 0.98]);
    await waitVersionAbove(page, v);
    await page.keyboard.press('Numpad5');
    await waitFor(page, 'the perspective camera', () => !window.__holey.camera.ortho);
    if (await page.isChecked(tid('ortho-toggle'))) throw new Error('numpad 5 left the Ortho box checked');
    // The screenshot button downloads a PNG of the view.
    const [download] = await Promise.all([page.waitForEvent('download', { timeout: 30000 }), page.click(tid('screenshot'))]);
    if (!/^holey-.*\.png$/.test(download.suggestedFilename())) throw new Error(`downloaded as ${download.suggestedFilename()}`);
    const saved = path.join(artifacts, '24-screenshot-button.png');
    await download.saveAs(saved);
    const png = fs.readFileSync(saved);
    if (png.subarray(0, 8).toString('hex') !== '89504e470d0a1a0a' || png.length < 2000) throw new Error(`the download is not a PNG picture (${png.length} bytes)`);
    const width = png.readUInt32BE(16), height = png.readUInt32BE(20);
    const canvasSize = await page.$eval(tid('canvas'), (c) => [c.width, c.height]);
    if (width !== canvasSize[0] || height !== canvasSize[1]) throw new Error(`the PNG is ${width}×${height}, the view ${canvasSize}`);
  }],

  ['sculpt: a fast drag lays a dab every spacing % of the radius; the stabilizer holds short moves; pen pressure is sent', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    await page.click(tid('tool-draw'));
    await setRange(page, 'radius', 10);
    await setRange(page, 'strength', 0.3);
    const radius = await page.evaluate(() => window.__holey.bbox.diag * 0.1);
    const A = [-0.4, 0, Math.sqrt(1 - 0.16)], B = [0.4, 0, Math.sqrt(1 - 0.16)];
    // One jump of the pointer from A to B: the dabs still cover the way.
    const framesFor = async (spacing) => {
      await page.fill(tid('stroke-spacing'), String(spacing));
      const f0 = await page.evaluate(() => window.__holey.framesSent);
      const v = await version(page);
      await dragThrough(page, A, B, { steps: 1 });
      await waitVersionAbove(page, v);
      const frames = (await page.evaluate(() => window.__holey.framesSent)) - f0;
      await clickForNewVersion(page, 'undo');
      return frames;
    };
    for (const spacing of [10, 50]) {
      const want = Math.floor(0.8 / ((spacing / 100) * radius));
      const got = await framesFor(spacing);
      // The dabs sit on the surface, slightly off the straight chord.
      if (Math.abs(got - want) > 1) throw new Error(`spacing ${spacing}%: ${got} frames for a jump of 0.8, not ${want}`);
    }
    await page.fill(tid('stroke-spacing'), '10');
    // The stabilizer: a 40 px wiggle within a 60 px string sends nothing.
    const short = async (lazy) => {
      await setRange(page, 'lazy-mouse', lazy);
      const a = await page.evaluate((p) => window.__holey.project(p), [0, 0, 1]);
      const f0 = await page.evaluate(() => window.__holey.framesSent);
      await page.mouse.move(a[0], a[1]);
      await page.mouse.down();
      for (let i = 1; i <= 8; i++) await page.mouse.move(a[0] + 5 * i, a[1]);
      await page.mouse.up();
      await waitFor(page, 'the end of the stroke', () => !window.__holey.stroking);
      return (await page.evaluate(() => window.__holey.framesSent)) - f0;
    };
    const held = await short(60);
    const free = await short(0);
    if (held !== 0 || free < 2) throw new Error(`a 40 px move sent ${held} frames with the stabilizer and ${free} without`);
    // Pen pressure (synthetic pen events): sent with stroke_begin and each
    // frame; a mouse sends none.
    const mouseSent = await page.evaluate(() => window.__holey.strokesSent.at(-1));
    if ('pressure' in mouseSent) throw new Error('a mouse stroke sent a pressure');
    await page.selectOption(tid('pressure-drives'), 'radius');
    const a = await page.evaluate((p) => window.__holey.project(p), A);
    const b = await page.evaluate((p) => window.__holey.project(p), B);
    const p0 = await page.evaluate(() => window.__holey.pressuresSent.length);
    const v = await version(page);
    await page.evaluate(([a, b]) => {
      const c = document.querySelector('[data-testid="canvas"]');
      const ev = (type, x, y, pressure) => c.dispatchEvent(new PointerEvent(type, {
        pointerId: 41, pointerType: 'pen', isPrimary: true, pressure, clientX: x, clientY: y,
        button: type === 'pointermove' ? -1 : 0, buttons: type === 'pointerup' ? 0 : 1, bubbles: true, cancelable: true,
      }));
      ev('pointerdown', a[0], a[1], 0.3);
      for (let i = 1; i <= 10; i++) ev('pointermove', a[0] + ((b[0] - a[0]) * i) / 10, a[1] + ((b[1] - a[1]) * i) / 10, 0.3 + 0.05 * i);
      ev('pointerup', b[0], b[1], 0);
    }, [a, b]);
    await waitFor(page, 'the end of the pen stroke', () => !window.__holey.stroking);
    await waitVersionAbove(page, v);
    const sent = await page.evaluate(() => window.__holey.strokesSent.at(-1));
    if (!(Math.abs(sent.pressure - 0.3) < 1e-6) || sent.pressure_drives !== 'radius') throw new Error(`the pen stroke began with ${JSON.stringify(sent)}`);
    const pressures = await page.evaluate((n) => window.__holey.pressuresSent.slice(n), p0);
    if (pressures.length < 5 || pressures.some((p) => !(p > 0.3 && p <= 0.81))) throw new Error(`frame pressures ${pressures}`);
    await page.selectOption(tid('pressure-drives'), 'strength');
    await page.screenshot({ path: path.join(artifacts, '25-pen.png') });
    // Shift-drag on the mesh smooths, whatever brush is chosen, and the
    // brush stays chosen.
    const before = await positions(page);
    const w = await version(page);
    await dragThrough(page, A, B, { modifiers: ['Shift'] });
    await waitVersionAbove(page, w);
    const smooth = await page.evaluate(() => window.__holey.strokesSent.at(-1));
    if (smooth.brush !== 'smooth' || !(smooth.strength > 0 && smooth.strength <= 1)) throw new Error(`Shift-drag sent ${JSON.stringify(smooth)}`);
    if (movedVertices(before, await positions(page)).length < 5) throw new Error('the Shift-drag moved nothing');
    if (!(await page.$eval(tid('tool-draw'), (b) => b.classList.contains('active')))) throw new Error('Shift-drag changed the chosen brush');
  }],

  ['sculpt: layer passed back and forth in one stroke rises to its height and stops; a new stroke lays the next layer on top', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    await page.click(tid('tool-layer'));
    await setRange(page, 'radius', 12);
    await setRange(page, 'strength', 0.5);
    const stats0 = await statsText(page);
    const before = await positions(page);
    const radius = await page.evaluate(() => window.__holey.bbox.diag * 0.12);
    const h = 0.5 * 0.25 * radius; // the first slab's height
    // How far each vertex rose along the sphere's normal (the brush normal
    // near the path's middle), and the highest.
    const rise = (after) => {
      let top = 0;
      for (let k = 0; k < before.length / 3; k++) top = Math.max(top, norm(after, k) - norm(before, k));
      return top;
    };
    const [A, B] = [[-0.25, 0.0, 0.97], [0.25, 0.0, 0.97]];
    const stroke = async (path) => {
      const v = await version(page);
      await dragPath(page, path);
      await waitVersionAbove(page, v);
      const sent = await page.evaluate(() => window.__holey.strokesSent.at(-1));
      // The slab's height: strength × LAYER_PER_RADIUS × the radius sent
      // (which follows the mesh's size, so it grows with the first slab).
      if (sent.brush !== 'layer' || Math.abs(sent.strength - 0.5 * 0.25 * sent.radius) > 1e-9) throw new Error(`sent ${JSON.stringify(sent)}`);
      return positions(page);
    };
    const undo = async () => {
      await clickForNewVersion(page, 'undo');
    };
    // One pass: the middle of the path rises to the slab's height.
    const once = rise(await stroke([A, B]));
    if (!(once > 0.85 * h && once < 1.02 * h)) throw new Error(`one pass rose ${once}, the slab is ${h}`);
    await undo();
    // There, back and there again, in one stroke: the same slab, not three.
    const thrice = await stroke([A, B, A, B]);
    const back = rise(thrice);
    console.log(`  layer: slab ${h.toFixed(4)}, one pass ${once.toFixed(4)}, three passes ${back.toFixed(4)}`);
    if (!(back < 1.02 * h && Math.abs(back - once) < 0.05 * h)) throw new Error(`three passes in one stroke rose ${back}, one pass ${once} (slab ${h})`);
    // A vertex under the path did not move farther than the slab either
    // (in any direction, so the plateau is not sideways drift).
    let far = 0;
    for (let k = 0; k < before.length / 3; k++) {
      const d = Math.hypot(thrice[3 * k] - before[3 * k], thrice[3 * k + 1] - before[3 * k + 1], thrice[3 * k + 2] - before[3 * k + 2]);
      far = Math.max(far, d);
    }
    if (far > 1.05 * h) throw new Error(`a vertex moved ${far}, more than the slab ${h}`);
    await page.screenshot({ path: path.join(artifacts, '26-layer-once.png') });
    // A new stroke starts a new layer on the last one (Blender: "a new
    // stroke … paints on top of the previous stroke").
    const twice = rise(await stroke([A, B]));
    if (!(twice > 1.7 * h && twice < 2.05 * h)) throw new Error(`a second stroke rose ${twice} in all, not two slabs of ${h}`);
    await page.screenshot({ path: path.join(artifacts, '26-layer-twice.png') });
    await undo();
    await undo();
    if ((await statsText(page)) !== stats0) throw new Error(`undo left "${await statsText(page)}", not "${stats0}"`);
  }],

  ['sculpt: hotkeys pick every brush (1 … 0, Shift+1 … 4, Blender\'s letters) and titles show them; mask edits undo and redo; the mask shades with the surface', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    await page.locator(tid('canvas')).focus();
    const active = () => page.$$eval('[data-tool].active', (bs) => bs.map((b) => b.dataset.tool));
    const keys = [
      ['1', 'inflate'], ['2', 'smooth'], ['3', 'grab'], ['4', 'move'], ['5', 'move-piece'], ['6', 'snake_hook'],
      ['7', 'draw'], ['8', 'clay'], ['9', 'crease'], ['0', 'flatten'],
      ['Shift+1', 'layer'], ['Shift+2', 'pinch'], ['Shift+3', 'scrape'], ['Shift+4', 'scale'],
      ['x', 'draw'], ['c', 'clay'], ['Shift+C', 'crease'], ['i', 'inflate'], ['s', 'smooth'], ['g', 'grab'],
      ['k', 'snake_hook'], ['l', 'layer'], ['p', 'pinch'], ['Shift+T', 'flatten'], ['m', 'mask'],
    ];
    for (const [key, tool] of keys) {
      await page.click(tid(tool === 'inflate' ? 'tool-smooth' : 'tool-inflate')); // start elsewhere
      await page.locator(tid('canvas')).focus();
      await page.keyboard.press(key);
      const on = await active();
      if (on.length !== 1 || on[0] !== tool) throw new Error(`${key} picked ${on}, not ${tool}`);
      // The button's title names the key (Shift+1 as "Shift+1", x as "X").
      const title = await page.$eval(`[data-tool="${tool}"]`, (b) => b.title);
      const shown = key.length === 1 ? key.toUpperCase() : key.replace(/\+(\w)$/, (_, c) => `+${c.toUpperCase()}`);
      if (!new RegExp(`[(, ]${shown.replace('+', '\\+')}[,)]`).test(title)) throw new Error(`${tool}'s title "${title}" does not name ${shown}`);
    }
    // Every brush button names at least one key.
    const silent = await page.$$eval('[data-panel="sculpt"] [data-tool]', (bs) => bs.filter((b) => !/\((\w|Shift\+)/.test(b.title)).map((b) => b.dataset.tool));
    if (silent.length) throw new Error(`no key in the titles of ${silent}`);

    // Mask edits are undo steps: paint, Ctrl+Z unmasks, Ctrl+Shift+Z masks again.
    await setRange(page, 'radius', 20);
    const replies = await page.evaluate(() => window.__holey.maskReplies.length);
    await dragThrough(page, [-0.3, 0.0, 0.954], [0.3, 0.0, 0.954]);
    await waitFor(page, 'the mask from the server', (n) => window.__holey.maskReplies.length > n, replies);
    const n = await page.evaluate(() => window.__holey.maskedCount);
    if (n < 10) throw new Error(`${n} vertices masked`);
    if (!(await page.evaluate(() => window.__holey.state.can_undo))) throw new Error('no undo after the mask paint');
    let v = await version(page);
    await page.keyboard.press('Control+Z');
    await waitVersionAbove(page, v);
    await waitFor(page, 'the mask undone', () => window.__holey.maskedCount === 0);
    v = await version(page);
    await page.keyboard.press('Control+Shift+Z');
    await waitVersionAbove(page, v);
    await waitFor(page, 'the mask redone', (m) => window.__holey.maskedCount === m, n);
    // Ctrl+I inverts, Alt+M clears, as in Blender; both undo.
    const nv = await page.evaluate(() => window.__holey.stats.vertices);
    await page.keyboard.press('Control+I');
    await waitFor(page, 'the inverted mask', (m) => window.__holey.maskedCount === m, nv - n);
    await page.keyboard.press('Alt+M');
    await waitFor(page, 'no mask', () => window.__holey.maskedCount === 0);
    v = await version(page);
    await page.keyboard.press('Control+Z');
    await waitFor(page, 'the inverted mask back', (m) => window.__holey.maskedCount === m, nv - n);

    // The mask shades with the surface: masked, the sphere's middle is
    // darker than unmasked, and its middle still differs from its rim
    // (a flat overlay would paint both one grey). Everything masked:
    await page.keyboard.press('Alt+M');
    await waitFor(page, 'no mask', () => window.__holey.maskedCount === 0);
    const spots = [[0, 0, 1], [0.93, 0, 0.37], [0, 0.93, 0.37]];
    await page.selectOption(tid('matcap-select'), 'studio');
    await waitFor(page, 'the studio material', () => window.__holey.camera.material === 'studio');
    const plain = await lumaAt(page, spots);
    await page.click(tid('mask-invert'));
    await waitFor(page, 'all masked', (m) => window.__holey.maskedCount === m, nv);
    for (const material of ['studio', 'clay']) {
      await page.selectOption(tid('matcap-select'), material);
      await waitFor(page, `the ${material} material`, (x) => window.__holey.camera.material === x, material);
      const masked = await lumaAt(page, spots);
      console.log(`  ${material}: unmasked ${plain.map((x) => x.toFixed(0))}, masked ${masked.map((x) => x.toFixed(0))}`);
      if (material === 'studio' && !(masked[0] < 0.75 * plain[0])) throw new Error(`masked, the middle reads ${masked[0]}, unmasked ${plain[0]}`);
      const spread = Math.max(...masked) - Math.min(...masked);
      if (!(spread > 12)) throw new Error(`${material}: the masked sphere reads ${masked} from middle to rim: flat`);
      await page.screenshot({ path: path.join(artifacts, `27-mask-${material}.png`) });
    }
    await page.selectOption(tid('matcap-select'), 'studio');
    // Half masked, for the picture: the rim between fades over a triangle.
    await page.click(tid('mask-clear'));
    await waitFor(page, 'no mask', () => window.__holey.maskedCount === 0);
    await page.evaluate(() => window.__holey.setView([0.5, 0.3, 1]));
    await page.click(tid('mask-paint'));
    await setRange(page, 'radius', 30);
    const r2 = await page.evaluate(() => window.__holey.maskReplies.length);
    await dragThrough(page, [-0.4, 0.5, 0.77], [0.5, -0.3, 0.81]);
    await waitFor(page, 'the mask from the server', (k) => window.__holey.maskReplies.length > k, r2);
    await page.waitForTimeout(100);
    await page.screenshot({ path: path.join(artifacts, '27-mask-half.png') });
    await page.click(tid('mask-clear'));
    await page.click(tid('tool-inflate'));
  }],

  ['bunny: one stroke of every brush at the default radius and strength shows in the picture and keeps the bunny whole', async (page) => {
    const file = path.join(meshesDir, 'stanford-bunny.obj');
    if (useMock || !fs.existsSync(file)) return 'SKIP';
    await page.reload();
    await page.waitForFunction(() => window.__holey?.frames > 0, null, { timeout: 30000 });
    const v0 = await version(page);
    await page.setInputFiles(tid('import-input'), file);
    await waitVersionAbove(page, v0, 60000);
    await setWorkspace(page, 'sculpt');
    await waitStats(page, /components 1 · genus 0 · boundary loops 5/);
    // The page's defaults, as a new user finds them.
    const defaults = await page.evaluate(() => ({
      radius: Number(document.querySelector('[data-testid="radius"]').value),
      strength: Number(document.querySelector('[data-testid="strength"]').value),
      remesh: Number(document.querySelector('[data-testid="remesh-detail"]').defaultValue),
    }));
    // Remeshing is on by default (earlier scenarios turned it off in the
    // server's session, which outlives the page).
    if (!(defaults.remesh > 0)) throw new Error('remeshing is off by default');
    await setRange(page, 'remesh-detail', defaults.remesh);
    await waitFor(page, 'remeshing on', (d) => window.__holey.state?.remesh?.detail === d, defaults.remesh);
    await page.evaluate(() => window.__holey.setView([0, 0, 1]));
    await page.waitForTimeout(100);
    const diag = await page.evaluate(() => window.__holey.bbox.diag);
    // Across the haunch, seen from the bunny's right side (+z), a stroke
    // about two brush radii long, as in scenario 10.
    const [A, B] = [[-0.01, 0.07, 0.07], [0.025, 0.085, 0.07]];
    const results = {};
    await page.screenshot({ path: path.join(artifacts, '28-bunny-before.png') });
    // The drag brushes follow the pointer: they pull the back up by one
    // radius, from a vertex just inside the top silhouette facing us (a
    // sideways drag over the haunch slides it through its neighbours,
    // which the engine turns into a topology change, as it should).
    const start = await page.evaluate(() => {
      const p = window.__holey.positions;
      let best = null;
      for (let k = 0; k < p.length; k += 3) {
        if (p[k + 2] > 0.035 && p[k] > -0.03 && p[k] < 0 && (!best || p[k + 1] > best[1])) best = [p[k], p[k + 1], p[k + 2]];
      }
      return best;
    });
    const up = [start[0], start[1] + 0.1 * diag, start[2]];
    const drags = new Set(['grab', 'move', 'snake_hook']);
    for (const tool of ['inflate', 'smooth', 'grab', 'move', 'snake_hook', 'draw', 'clay', 'crease', 'flatten', 'pinch', 'scrape', 'layer', 'scale']) {
      await page.click(tid(`tool-${tool.replace('_', '-')}`));
      const r = await page.evaluate(() => [Number(document.querySelector('[data-testid="radius"]').value), Number(document.querySelector('[data-testid="strength"]').value)]);
      if (r[0] !== defaults.radius || r[1] !== defaults.strength) throw new Error(`${tool} starts at radius ${r[0]}, strength ${r[1]}, not the defaults`);
      const before = await positions(page);
      await viewPicture(page);
      const v = await version(page);
      await dragPath(page, drags.has(tool) ? [start, up] : [A, B], { steps: 20, pause: 20 });
      await waitVersionAbove(page, v, 60000);
      const changed = await viewPicture(page, true);
      const moved = farthestMove(before, await positions(page), diag / 200);
      const stats = parseStats(await statsText(page));
      const whole = /components 1 · genus 0 · boundary loops 5/.test(await statsText(page));
      results[tool] = { changedPixels: changed, movedShare: round(moved / diag, 4), whole, V: stats.V };
      await page.screenshot({ path: path.join(artifacts, `28-bunny-${tool}.png`) });
      await clickForNewVersion(page, 'undo');
    }
    console.log(`  defaults ${JSON.stringify(defaults)}; per brush ${JSON.stringify(results)}`);
    // Visible: hundreds of pixels change. Not destructive: one piece, five
    // holes, genus 0, and no point farther than 8% of the size from where
    // the surface was (the drags: their pull, a tenth, and a margin).
    const bad = Object.entries(results).filter(([tool, r]) =>
      !r.whole || r.changedPixels < 500 || r.movedShare > (drags.has(tool) ? 0.15 : 0.08));
    fs.writeFileSync(path.join(artifacts, '28-bunny-defaults.json'), JSON.stringify({ defaults, results }, null, 2) + '\n');
    if (bad.length) throw new Error(`not visible, or destructive: ${JSON.stringify(Object.fromEntries(bad))}`);
  }],

  ['sculpt: symmetry Y and Z together mirror a stroke into four places; symmetry X about the mesh centre follows a moved sphere', async (page) => {
    if (useMock) return 'SKIP';
    await sculptSphere(page);
    await page.click(tid('tool-draw'));
    await setRange(page, 'radius', 10);
    await setRange(page, 'strength', 1);
    for (const a of ['x', 'y', 'z']) await page.uncheck(tid(`symmetry-${a}`));
    await page.check(tid('symmetry-y'));
    await page.check(tid('symmetry-z'));
    await page.selectOption(tid('symmetry-about'), 'origin');
    let before = await positions(page);
    let v = await version(page);
    // In the +y, +z quarter only (seen from +z).
    await dragThrough(page, [-0.2, 0.5, 0.84], [0.2, 0.45, 0.87]);
    await waitVersionAbove(page, v);
    let sent = await page.evaluate(() => window.__holey.strokesSent.at(-1));
    if (sent.symmetry !== 'yz' || sent.symmetry_about !== 'origin') throw new Error(`sent ${JSON.stringify(sent)}`);
    let after = await positions(page);
    let moved = movedVertices(before, after);
    const quarter = (sy, sz) => moved.filter((k) => sy * before[3 * k + 1] > 0.2 && sz * before[3 * k + 2] > 0.2).length;
    const counts = [quarter(1, 1), quarter(-1, 1), quarter(1, -1), quarter(-1, -1)];
    if (counts[0] < 5 || counts.some((c) => c !== counts[0])) throw new Error(`moved per quarter (+y+z, −y+z, +y−z, −y−z): ${counts}`);
    for (const axis of [1, 2]) {
      const worst = mirrorDistanceAcross(after, axis, 0);
      if (worst > 1e-5) throw new Error(`across ${'xyz'[axis]} = 0, a vertex is ${worst} from the nearest mirror of another`);
    }
    await page.screenshot({ path: path.join(artifacts, '29-symmetry-yz.png') });
    await clickForNewVersion(page, 'undo');
    for (const a of ['y', 'z']) await page.uncheck(tid(`symmetry-${a}`));

    // Move the whole sphere to the right, then draw with symmetry X about
    // the mesh's centre: the result mirrors across the sphere's own middle.
    await page.click(tid('tool-move-piece'));
    v = await version(page);
    await dragThrough(page, [0, 0, 1], [0.6, 0, 1]);
    await waitVersionAbove(page, v);
    const c = await page.evaluate(() => window.__holey.bbox.center);
    if (!(c[0] > 0.3)) throw new Error(`the sphere's centre is at ${c}, not moved right`);
    await page.click(tid('tool-draw'));
    await page.check(tid('symmetry-x'));
    await page.selectOption(tid('symmetry-about'), 'centre');
    before = await positions(page);
    v = await version(page);
    const at = (dx, y) => [c[0] + dx, y, Math.sqrt(1 - dx * dx - y * y)];
    await dragThrough(page, at(0.45, 0.3), at(0.55, -0.2));
    await waitVersionAbove(page, v);
    sent = await page.evaluate(() => window.__holey.strokesSent.at(-1));
    if (sent.symmetry !== 'x' || sent.symmetry_about !== 'centre') throw new Error(`sent ${JSON.stringify(sent)}`);
    after = await positions(page);
    moved = movedVertices(before, after);
    const right = moved.filter((k) => before[3 * k] > c[0] + 0.2).length, left = moved.filter((k) => before[3 * k] < c[0] - 0.2).length;
    if (right < 5 || right !== left) throw new Error(`moved ${right} vertices right of the centre and ${left} left of it`);
    const worst = mirrorDistanceAcross(after, 0, c[0]);
    if (worst > 1e-5) throw new Error(`across x = ${c[0]}, a vertex is ${worst} from the nearest mirror of another`);
    await page.screenshot({ path: path.join(artifacts, '29-symmetry-x-centre.png') });
    await page.uncheck(tid('symmetry-x'));
    await page.selectOption(tid('symmetry-about'), 'origin');
    for (let i = 0; i < 2; i++) {
      await clickForNewVersion(page, 'undo');
    }
  }],

  ['Convex hull and dual convex hull of a cube: the cube, then an octahedron three times as wide; undo; a flat mesh is refused', async (page) => {
    if (useMock) return 'SKIP'; // the mock server has no hulls
    await setWorkspace(page, 'model');
    for (const id of ['op-hull', 'op-dual-hull']) {
      const title = await page.getAttribute(tid(id), 'title');
      if (!title || title.length < 20) throw new Error(`${id} has no tooltip (title "${title}")`);
    }
    await createPrimitive(page, '@cube');
    await waitStats(page, /\bV 8 · E 12 · F 6\b/);
    const { V, E, F } = parseStats(await statsText(page));
    const width = await page.evaluate(() => window.__holey.bbox.max[0] - window.__holey.bbox.min[0]);
    const undo = async () => {
      await clickForNewVersion(page, 'undo');
      await waitStats(page, new RegExp(`\\bV ${V} · E ${E} · F ${F}\\b.*genus 0(?!\\d)`));
    };
    // The hull of a convex polyhedron's corners is the polyhedron: a new
    // version with the same counts.
    await clickForNewVersion(page, 'op-hull');
    await waitStats(page, new RegExp(`\\bV ${V} · E ${E} · F ${F}\\b`));
    await undo();
    // The dual hull has one face per corner of the hull; on a regular
    // polyhedron it is the polar dual, so a vertex per face and an edge
    // per edge: F, E, V (the octahedron, 6 − 12 + 8 = 2, genus 0).
    await clickForNewVersion(page, 'op-dual-hull');
    await waitStats(page, new RegExp(`\\bV ${F} · E ${E} · F ${V}\\b.*genus 0(?!\\d)`));
    // The tangent plane at the corner (h, h, h) is x + y + z = 3h: the
    // octahedron's corners are on the axes, 3h out, three times as wide.
    const wide = await page.evaluate(() => window.__holey.bbox.max[0] - window.__holey.bbox.min[0]);
    if (Math.abs(wide - 3 * width) > 1e-4 * width) throw new Error(`the dual hull is ${wide} wide, not 3 × ${width}`);
    await waitFor(page, 'a toast naming the dual convex hull',
      () => [...document.querySelectorAll('[data-testid="toast"]')].some((t) => /dual convex hull/.test(t.textContent)));
    await page.evaluate(() => window.__holey.setView([1, 0.8, 1.2]));
    await page.waitForTimeout(200);
    await page.screenshot({ path: path.join(artifacts, '30-dual-hull.png') });
    await undo();
    // Points on one plane bound no solid: an error toast, the plane unchanged.
    await createPrimitive(page, '@plane');
    const flat = await statsText(page);
    const v = await version(page);
    await page.click(tid('op-dual-hull'));
    await waitFor(page, 'an error toast saying the points lie on one plane', () =>
      [...document.querySelectorAll('[data-testid="toast-error"]')].some((t) => /one plane/.test(t.textContent)));
    if ((await version(page)) !== v || (await statsText(page)) !== flat) throw new Error('the refused hull changed the document');
  }],
  ['Handle tool: a Bézier tunnel through a cube of 3 × 3 quads a side; six cubes joined through a hub by a multi-face handle, previewed, then made with each curve; undo', async (page) => {
    if (useMock) return 'SKIP';
    // A cube of 3 × 3 quads a side (6n² + 2, 12n², 6n²), tunnelled between
    // the middle quads of its +z and −z sides, found by their normals and
    // centroids in the frame.
    await setWorkspace(page, 'model');
    const v0 = await version(page);
    await page.evaluate(() => window.__holey.request('primitive', { spec: '@cube:3' }));
    await waitVersionAbove(page, v0);
    await waitStats(page, /\bV 56 · E 108 · F 54\b/);
    const { V, E, F } = parseStats(await statsText(page));
    let faces = faceFrames(await page.evaluate(() => window.__holey.frameArrays));
    const middle = (z) => {
      const off = (f) => Math.hypot(f.centre[0], f.centre[1]);
      const side = faces.flatMap((f, i) => (f.normal[2] * z > 0 ? [i] : []));
      return side.reduce((best, i) => (off(faces[i]) < off(faces[best]) ? i : best), side[0]);
    };
    await page.evaluate((f) => window.__holey.selectFaces(f), [middle(1), middle(-1)]);
    // A handle of s segments between quads adds 4(s − 1) vertices,
    // 4(2s − 1) edges and 4s − 2 faces; on one body, one to the genus.
    const s = 3;
    await page.fill(tid('handle-segments'), String(s));
    await page.fill(tid('handle-w1'), '-1');
    await page.fill(tid('handle-w2'), '-1');
    await page.selectOption(tid('handle-curve'), 'bezier');
    await clickForNewVersion(page, 'handle-commit');
    await waitStats(page, new RegExp(`\\bV ${V + 4 * (s - 1)} · E ${E + 4 * (2 * s - 1)} · F ${F + 4 * s - 2}\\b.*genus 1(?!\\d)`));
    await waitFor(page, 'a toast naming the Bézier handle', () =>
      [...document.querySelectorAll('[data-testid="toast"]')].some((t) => /Bézier handle/.test(t.textContent)));
    await page.evaluate(() => window.__holey.setView([0.5, 0.4, 1]));
    await page.waitForTimeout(200);
    await page.screenshot({ path: path.join(artifacts, '31-bezier-tunnel.png') });

    // Six cubes around the origin, each side looking at it selected.
    const file = path.join(artifacts, 'six-cubes.obj');
    fs.writeFileSync(file, sixCubesObj());
    const v = await version(page);
    await page.setInputFiles(tid('import-input'), file);
    await waitVersionAbove(page, v);
    await waitStats(page, /\bV 48 · E 72 · F 36 · components 6\b/);
    faces = faceFrames(await page.evaluate(() => window.__holey.frameArrays));
    const facing = faces.flatMap((f, i) => (dot(f.normal, f.centre) < 0 ? [i] : []));
    if (facing.length !== 6) throw new Error(`${facing.length} faces look at the centre, not 6`);
    // Three faces are neither a pair nor a hub's worth: the page says so.
    await page.evaluate((f) => window.__holey.selectFaces(f), facing.slice(0, 3));
    await page.click(tid('handle-commit'));
    await waitFor(page, 'an error toast asking for two or four or more faces', () =>
      [...document.querySelectorAll('[data-testid="toast-error"]')].some((t) => /four or more/.test(t.textContent)));
    await page.evaluate((f) => window.__holey.selectFaces(f), facing);
    await page.fill(tid('handle-w1'), '0.5');
    await page.fill(tid('handle-w2'), '0.5');
    await page.fill(tid('handle-hub-scale'), '0.5');
    await page.selectOption(tid('handle-curve'), 'hermite');
    // The preview shows the hub and handles and commits nothing.
    const previews = await page.evaluate(() => window.__holey.previewFrames);
    await page.click(tid('op-handle'));
    await waitFor(page, 'the preview frame', (n) => window.__holey.previewFrames > n, previews);
    await page.evaluate(() => window.__holey.setView([1, 0.8, 0.6]));
    await page.waitForTimeout(200);
    await page.screenshot({ path: path.join(artifacts, '31-multi-handle-preview.png') });
    await waitStats(page, /\bV 48 · E 72 · F 36 · components 6\b/);
    // The hub is the octahedron's dual, a cube (8 / 12 / 6), a quad facing
    // each selected quad; seven bodies joined by six handles: one sphere.
    const k = 6;
    const joined = new RegExp(`\\bV ${48 + 8 + k * 4 * (s - 1)} · E ${72 + 12 + k * 4 * (2 * s - 1)} · F ${36 + 6 + k * (4 * s - 2)} · components 1 · genus 0(?!\\d)`);
    for (const curve of ['hermite', 'bezier']) {
      await page.selectOption(tid('handle-curve'), curve);
      await page.evaluate((f) => window.__holey.selectFaces(f), facing);
      await clickForNewVersion(page, 'handle-commit');
      await waitStats(page, joined);
      await page.evaluate(() => window.__holey.setView([1, 0.8, 0.6]));
      await page.waitForTimeout(200);
      await page.screenshot({ path: path.join(artifacts, `31-multi-handle-${curve}.png`) });
      await clickForNewVersion(page, 'undo');
      await waitStats(page, /\bV 48 · E 72 · F 36 · components 6\b/);
    }
  }],
];

// ---- run --------------------------------------------------------------------------

const server = startServer();
let browser;
let failed = 0, passed = 0, skipped = 0;
try {
  const url = await server.url;
  console.log(`server: ${url.replace(/token=[^&]+/, 'token=…')}${useMock ? ' (mock)' : ''}`);
  if (!useMock) await checkAccess(url);
  browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
      // Chromium ≥ 137 only offers software WebGL (SwiftShader) when asked.
      '--enable-unsafe-swiftshader'],
  });
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 }, acceptDownloads: true });
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(`pageerror: ${e.message}`));
  // The text side of the WebSocket conversation, for debugging failures.
  const wsLog = fs.createWriteStream(path.join(artifacts, 'ws.log'));
  page.on('websocket', (ws) => {
    const t = () => (performance.now() / 1000).toFixed(3);
    ws.on('framesent', (f) => {
      wsLog.write(`${t()} > ${typeof f.payload === 'string' ? f.payload : `<${f.payload.length} bytes>`}\n`);
      if (typeof f.payload === 'string') keepStroke(f.payload);
    });
    ws.on('framereceived', (f) => {
      wsLog.write(`${t()} < ${typeof f.payload === 'string' ? f.payload : `<${f.payload.length} bytes>`}\n`);
      if (typeof f.payload === 'string') keepAnswer(f.payload);
    });
    ws.on('close', () => wsLog.write(`${t()} closed\n`));
  });
  if (only && !only.has(1)) {
    await page.goto(url);
    await page.waitForFunction(() => window.__holey?.frames > 0, null, { timeout: 30000 });
  }

  for (const [i, [name, fn]] of scenarios.entries()) {
    const n = i + 1;
    if (only && !only.has(n)) continue;
    const t0 = Date.now();
    sentStrokes.length = 0;
    let outcome;
    try {
      outcome = (await fn(page, url)) === 'SKIP' ? 'SKIP' : 'PASS';
    } catch (e) {
      outcome = 'FAIL';
      console.log(`  ${String(e.message || e).split('\n').join('\n  ')}`);
    }
    keepStrokes(n, outcome === 'FAIL');
    if (outcome === 'PASS') passed++;
    else if (outcome === 'FAIL') failed++;
    else skipped++;
    console.log(`${outcome} ${n}. ${name} (${((Date.now() - t0) / 1000).toFixed(1)} s)`);
    await page.screenshot({ path: path.join(artifacts, `scenario-${n}.png`) }).catch(() => {});
  }
  if (consoleErrors.length) console.log(`console errors during the run: ${consoleErrors.join(' | ')}`);
} catch (e) {
  failed++;
  console.log(`FAIL setup: ${e.message}`);
} finally {
  await browser?.close().catch(() => {});
  server.child.kill();
  fs.rmSync(server.stateDir, { recursive: true, force: true });
}
console.log(`${passed} passed, ${failed} failed${skipped ? `, ${skipped} skipped` : ''}`);
process.exit(failed ? 1 : 0);

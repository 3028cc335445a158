// A stand-in for `holey serve` for front-end development without the Rust
// build: it speaks the same protocol (PROTOCOL.md) over a few meshes, with
// stats from Euler's formula and a crude inflate brush. It is NOT used by
// the real end-to-end tests, which run against the real server.
//
//   node e2e/mock-server.mjs [--port 8080] [--web dist]

import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { WebSocketServer } from 'ws';
import { encodeFrame, FLAG_POSITIONS_ONLY } from '../src/frame.js';

const arg = (name, dflt) => {
  const i = process.argv.indexOf(name);
  return i >= 0 ? process.argv[i + 1] : dflt;
};
const port = Number(arg('--port', 8080));
const webDir = path.resolve(arg('--web', 'dist'));

// ---- meshes (polygon lists) ---------------------------------------------------

function cube() {
  const p = [];
  for (let i = 0; i < 8; i++) p.push([i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1]);
  const f = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
  return { p, f };
}
function tetrahedron() {
  return { p: [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], f: [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]] };
}
function torus(n = 16, m = 8, R = 1, r = 0.4) {
  const p = [], f = [];
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < m; j++) {
      const u = (i / n) * 2 * Math.PI, v = (j / m) * 2 * Math.PI;
      p.push([(R + r * Math.cos(v)) * Math.cos(u), r * Math.sin(v), (R + r * Math.cos(v)) * Math.sin(u)]);
      const a = i * m + j, b = ((i + 1) % n) * m + j, c = ((i + 1) % n) * m + ((j + 1) % m), d = i * m + ((j + 1) % m);
      f.push([a, d, c, b]);
    }
  }
  return { p, f };
}
function sphere(level = 3) {
  // Cube projected onto the sphere, each side an n×n grid.
  const n = 2 ** level, p = [], f = [], key = new Map();
  const vid = (x, y, z) => {
    const k = `${x},${y},${z}`;
    if (!key.has(k)) {
      const l = Math.hypot(x, y, z);
      key.set(k, p.length);
      p.push([x / l, y / l, z / l]);
    }
    return key.get(k);
  };
  const sides = [[0, 1, 2, 1], [0, 1, 2, -1], [1, 2, 0, 1], [1, 2, 0, -1], [2, 0, 1, 1], [2, 0, 1, -1]];
  for (const [a, b, c, s] of sides) {
    const at = (i, j) => {
      const v = [0, 0, 0];
      v[a] = -1 + (2 * i) / n; v[b] = -1 + (2 * j) / n; v[c] = s;
      return vid(...v.map((x) => Math.round(x * n) / n));
    };
    for (let i = 0; i < n; i++) for (let j = 0; j < n; j++) {
      const q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
      f.push(s > 0 ? q : q.reverse());
    }
  }
  return { p, f };
}
const PRIMS = [
  { name: 'cube', spec: '@cube', about: 'unit cube', make: cube },
  { name: 'tetrahedron', spec: '@tetrahedron', about: 'regular tetrahedron', make: tetrahedron },
  { name: 'torus', spec: '@torus', about: 'genus-1 torus', make: torus },
  { name: 'sphere', spec: '@sphere', about: 'quad sphere (@sphere:N for detail)', make: sphere },
];

function stats(m) {
  const edges = new Set();
  for (const f of m.f) f.forEach((a, i) => { const b = f[(i + 1) % f.length]; edges.add(a < b ? `${a},${b}` : `${b},${a}`); });
  const chi = m.p.length - edges.size + m.f.length;
  return {
    vertices: m.p.length, edges: edges.size, faces: m.f.length,
    triangles: m.f.reduce((s, f) => s + f.length - 2, 0),
    components: 1, genus: (2 - chi) / 2, boundary_loops: 0, closed: true, manifold: true,
  };
}

function triangulate(m) {
  return { p: m.p, f: m.f.flatMap((f) => f.slice(1, -1).map((_, k) => [f[0], f[k + 1], f[k + 2]])) };
}

function frameOf(m, version, flags = 0, sparse = null) {
  const tris = [], triFace = [], edges = new Map();
  m.f.forEach((f, fi) => {
    for (let k = 1; k + 1 < f.length; k++) { tris.push(f[0], f[k], f[k + 1]); triFace.push(fi); }
    f.forEach((a, i) => { const b = f[(i + 1) % f.length]; edges.set(a < b ? `${a},${b}` : `${b},${a}`, [a, b]); });
  });
  // The sculpt mask, on whole frames of the sculpt workspace (as the real server).
  const masked = doc.workspace === 'sculpt' && doc.mask.size ? m.p.map((v) => (doc.mask.has(v.join(',')) ? 1 : 0)) : null;
  const sculptMask = masked && masked.includes(1) ? masked : null;
  return encodeFrame({
    flags, version, positions: m.p.flat(), tris, triFace, edges: [...edges.values()].flat(), nf: m.f.length, sparse, sculptMask,
  });
}

function parseObj(text) {
  const p = [], f = [];
  for (const line of text.split('\n')) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'v') p.push(w.slice(1, 4).map(Number));
    else if (w[0] === 'f') f.push(w.slice(1).map((t) => { const i = parseInt(t, 10); return i < 0 ? p.length + i : i - 1; }));
  }
  if (!f.length) throw new Error('no faces in the OBJ file');
  return { p, f };
}

// ---- document -------------------------------------------------------------------

// `mask`: the sculpt mask as exact positions ("x,y,z").
const doc = { mesh: cube(), workspace: 'model', version: 1, undo: [], redo: [], remesh: 0.5, mask: new Set() };
const clients = new Set();
let stroke = null;

const state = () => JSON.stringify({
  type: 'state', version: doc.version, workspace: doc.workspace, mode: 'normal',
  can_undo: doc.undo.length > 0, can_redo: doc.redo.length > 0, stats: stats(doc.mesh), busy: null,
  remesh: { detail: doc.remesh },
});
const clone = (m) => ({ p: m.p.map((v) => [...v]), f: m.f.map((f) => [...f]) });
function commit(mesh, workspace = doc.workspace) {
  doc.undo.push({ mesh: doc.mesh, workspace: doc.workspace });
  doc.redo = [];
  doc.mesh = mesh;
  doc.workspace = workspace;
  doc.version++;
  broadcast();
}
function broadcast() {
  for (const c of clients) {
    c.send(state());
    c.send(frameOf(doc.mesh, doc.version));
  }
}

function handle(ws, msg) {
  const ok = (extra = {}) => ws.send(JSON.stringify({ type: 'ok', id: msg.id, ...extra }));
  const err = (message) => ws.send(JSON.stringify({ type: 'error', id: msg.id, message }));
  switch (msg.op) {
    case 'hello':
      ws.send(state());
      ws.send(frameOf(doc.mesh, doc.version));
      return ok();
    case 'primitives':
      return ok({ primitives: PRIMS.map(({ name, spec, about }) => ({ name, spec, about })) });
    case 'primitive': {
      const [name, lvl] = String(msg.spec).split(':');
      const pr = PRIMS.find((q) => q.spec === name);
      if (!pr) return err(`unknown primitive ${msg.spec}`);
      let m = pr.make(lvl ? Number(lvl) : undefined);
      if (doc.workspace === 'sculpt') m = triangulate(m);
      commit(m);
      return ok();
    }
    case 'workspace':
      if (msg.workspace === doc.workspace) return ok();
      commit(msg.workspace === 'sculpt' ? triangulate(doc.mesh) : doc.mesh, msg.workspace);
      return ok();
    case 'undo':
    case 'redo': {
      const from = msg.op === 'undo' ? doc.undo : doc.redo, to = msg.op === 'undo' ? doc.redo : doc.undo;
      if (!from.length) return err(`nothing to ${msg.op}`);
      to.push({ mesh: doc.mesh, workspace: doc.workspace });
      ({ mesh: doc.mesh, workspace: doc.workspace } = from.pop());
      doc.version++;
      broadcast();
      return ok();
    }
    case 'set_remesh':
      doc.remesh = msg.detail;
      for (const c of clients) c.send(state());
      return ok();
    case 'stroke_begin':
      if (doc.workspace !== 'sculpt') return err('sculpt brushes need the sculpt workspace');
      stroke = { ...msg, before: clone(doc.mesh), mesh: clone(doc.mesh) };
      return ok();
    case 'stroke_frame': {
      if (!stroke) return err('no stroke');
      const t0 = performance.now();
      const r = stroke.radius;
      const moved = new Set();
      // `points`: further dabs after `point`, applied in order (PROTOCOL.md).
      for (const [x, y, z] of [msg.point, ...(msg.points ?? [])]) {
        for (const [i, v] of stroke.mesh.p.entries()) {
          const d = Math.hypot(v[0] - x, v[1] - y, v[2] - z);
          if (d >= r || doc.mask.has(v.join(','))) continue;
          moved.add(i);
          const l = Math.hypot(...v) || 1, w = (1 - d / r) ** 2 * stroke.strength * 0.05 * r;
          v[0] += (v[0] / l) * w; v[1] += (v[1] / l) * w; v[2] += (v[2] / l) * w;
        }
      }
      doc.mesh = stroke.mesh;
      // Like the real server: only the moved vertices when few of them moved.
      const sparse = moved.size < 0.75 * stroke.mesh.p.length;
      ws.send(frameOf(doc.mesh, doc.version, FLAG_POSITIONS_ONLY, sparse ? [...moved].sort((a, b) => a - b) : null));
      return ok({ ms: performance.now() - t0 });
    }
    case 'stroke_end': {
      if (!stroke) return err('no stroke');
      const m = stroke.mesh;
      doc.mesh = stroke.before;
      stroke = null;
      commit(m);
      return ok();
    }
    case 'mask_paint':
    case 'mask_clear':
    case 'mask_invert': {
      if (doc.workspace !== 'sculpt') return err('masking works in the sculpt workspace; switch to it first');
      const keys = doc.mesh.p.map((v) => v.join(','));
      if (msg.op === 'mask_clear') doc.mask = new Set();
      else if (msg.op === 'mask_invert') doc.mask = new Set(keys.filter((k) => !doc.mask.has(k)));
      else {
        const centres = msg.points ?? [msg.point], r = msg.radius;
        doc.mesh.p.forEach((v, i) => {
          if (!centres.some((c) => Math.hypot(v[0] - c[0], v[1] - c[1], v[2] - c[2]) <= r)) return;
          if (msg.erase) doc.mask.delete(keys[i]);
          else doc.mask.add(keys[i]);
        });
      }
      for (const c of clients) c.send(frameOf(doc.mesh, doc.version));
      return ok({ masked: keys.filter((k) => doc.mask.has(k)).length });
    }
    case 'remesh_schemes':
      // Two of the real server's list, so that the Remesh panel fills in;
      // remeshing itself is not mocked.
      return ok({
        max_levels: 8,
        schemes: [
          { name: 'dual', title: 'Dual', closed_only: true, params: [] },
          {
            name: 'corner-cutting', title: 'Corner cutting', closed_only: false,
            params: [{ name: 'corner_cutting_alpha', label: 'tension α', type: 'number', default: 0.5625, min: null, max: null }],
          },
        ],
      });
    case 'cancel':
      return ok();
    default:
      return err(`the mock server does not implement "${msg.op}"`);
  }
}

// ---- HTTP -----------------------------------------------------------------------

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.svg': 'image/svg+xml' };
const server = http.createServer((req, res) => {
  const url = new URL(req.url, 'http://x');
  const json = (code, body) => {
    res.writeHead(code, { 'Content-Type': 'application/json' });
    res.end(JSON.stringify(body));
  };
  if (url.pathname === '/api/health') return json(200, { ok: true });
  if (url.pathname === '/api/import' && req.method === 'POST') {
    const chunks = [];
    req.on('data', (c) => chunks.push(c));
    req.on('end', () => {
      try {
        const m = parseObj(Buffer.concat(chunks).toString('utf8'));
        commit(doc.workspace === 'sculpt' ? triangulate(m) : m);
        json(200, { ok: true });
      } catch (e) {
        json(400, { ok: false, error: e.message });
      }
    });
    return;
  }
  if (url.pathname === '/api/export') {
    const m = doc.mesh;
    const text = m.p.map((v) => `v ${v.join(' ')}`).concat(m.f.map((f) => `f ${f.map((i) => i + 1).join(' ')}`)).join('\n') + '\n';
    res.writeHead(200, { 'Content-Type': 'text/plain', 'Content-Disposition': 'attachment; filename="holey.obj"' });
    return res.end(text);
  }
  const file = path.join(webDir, url.pathname === '/' ? 'index.html' : path.normalize(url.pathname));
  if (!file.startsWith(webDir) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
    res.writeHead(404);
    return res.end('not found');
  }
  res.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream' });
  fs.createReadStream(file).pipe(res);
});

const wss = new WebSocketServer({ server, path: '/ws' });
wss.on('connection', (ws) => {
  clients.add(ws);
  ws.send(state());
  ws.on('close', () => clients.delete(ws));
  ws.on('message', (data, isBinary) => {
    if (isBinary) return;
    try {
      handle(ws, JSON.parse(String(data)));
    } catch (e) {
      ws.send(JSON.stringify({ type: 'error', id: null, message: e.message }));
    }
  });
});
server.listen(port, '127.0.0.1', () => {
  console.log(`holey serve: listening on http://127.0.0.1:${server.address().port}/`);
});

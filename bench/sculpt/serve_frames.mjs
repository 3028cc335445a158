// Replays a stroke file through `holey serve`, as the modeller's page sends
// it: the mesh imported over HTTP, the sculpt workspace, then for every
// stroke `stroke_begin`, one `stroke_frame` per recorded frame (its dabs
// together) and `stroke_end`, each request awaited before the next. Prints
// per stroke the request times (sent to answered, the frame's bytes
// included) beside the server's own frame times (`ms` of the answers). The
// server derives the remeshing range from the mesh, as it does for a user.
//
//   node --experimental-websocket bench/sculpt/serve_frames.mjs HOLEY MESH STROKES.json
//
// (Node 20 needs the flag for its WebSocket; from Node 22 it is built in.)
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

const [holey, meshPath, strokesPath] = process.argv.slice(2);
if (!strokesPath) {
  console.error('usage: serve_frames.mjs HOLEY MESH STROKES.json');
  process.exit(2);
}
const token = 'serve-frames-0123456789';
const stateDir = fs.mkdtempSync(path.join(os.tmpdir(), 'holey-serve-frames-'));
const server = spawn(holey, ['serve', '--port', '0', '--token', token, '--state-dir', stateDir], {
  stdio: ['ignore', 'pipe', 'inherit'],
});
const port = await new Promise((resolve, reject) => {
  let seen = '';
  server.on('exit', (code) => reject(new Error(`holey serve exited with ${code}`)));
  server.stdout.on('data', (d) => {
    seen += d;
    const m = seen.match(/127\.0\.0\.1:(\d+)/);
    if (m) resolve(m[1]);
  });
});
const base = `http://127.0.0.1:${port}`;
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
try {
  let t = performance.now();
  const imported = await fetch(`${base}/api/import?name=${path.basename(meshPath)}&token=${token}`, {
    method: 'POST',
    body: fs.readFileSync(meshPath),
  });
  if (!imported.ok) throw new Error(`import: ${imported.status} ${await imported.text()}`);
  console.log(`import ${(performance.now() - t).toFixed(0)} ms`);
  const ws = new WebSocket(`ws://127.0.0.1:${port}/ws?token=${token}`);
  ws.binaryType = 'arraybuffer';
  const waiting = new Map();
  let id = 0;
  ws.onmessage = (ev) => {
    if (typeof ev.data !== 'string') return;
    const m = JSON.parse(ev.data);
    const w = waiting.get(m.id);
    if (w && (m.type === 'ok' || m.type === 'error')) {
      waiting.delete(m.id);
      w(m);
    }
  };
  await new Promise((resolve) => (ws.onopen = resolve));
  const timed = async (op, fields = {}) => {
    const start = performance.now();
    const answer = await new Promise((resolve) => {
      waiting.set(++id, resolve);
      ws.send(JSON.stringify({ id, op, ...fields }));
    });
    if (answer.type === 'error') throw new Error(`${op}: ${answer.message}`);
    return [performance.now() - start, answer];
  };
  let [ms] = await timed('workspace', { workspace: 'sculpt' });
  console.log(`sculpt workspace ${ms.toFixed(0)} ms`);
  const file = JSON.parse(fs.readFileSync(strokesPath, 'utf8'));
  for (const [k, s] of file.strokes.entries()) {
    const counts = s.frames ?? s.path.map(() => 1);
    const frames = [];
    let at = 0;
    for (const c of counts) {
      frames.push(s.path.slice(at, at + c));
      at += c;
    }
    const [begin, first] = await timed('stroke_begin', {
      brush: s.brush,
      radius: s.radius,
      strength: s.strength,
      point: frames[0][0],
    });
    const requests = [];
    const own = [];
    for (const f of frames.slice(1)) {
      const fields = { point: f[0] };
      if (f.length > 1) fields.points = f.slice(1);
      const [took, answer] = await timed('stroke_frame', fields);
      requests.push(took);
      own.push(answer.ms);
    }
    const [end] = await timed('stroke_end');
    console.log(
      `stroke ${k} (${s.brush}): begin ${begin.toFixed(1)} ms (its frame ${first.ms.toFixed(1)}); ` +
        `${requests.length} frames: request median ${median(requests).toFixed(1)} ms, slowest ` +
        `${Math.max(...requests).toFixed(1)}; the server's frame median ${median(own).toFixed(1)} ms; ` +
        `end ${end.toFixed(1)} ms`,
    );
  }
  ws.close();
} finally {
  server.kill();
  fs.rmSync(stateDir, { recursive: true, force: true });
}

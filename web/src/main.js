// The modeler page: wires the DOM controls, the 3D view and the server
// connection together. The server owns the document; this page only shows
// the frames it is sent and turns gestures into requests (PROTOCOL.md).

import { Viewer } from './viewer.js';
import { Connection } from './connection.js';
import { parseFrame, applySparse, applyPatch, isCommit, FLAG_PATCH, FLAG_SPARSE } from './frame.js';

const $ = (id) => document.querySelector(`[data-testid="${id}"]`);
const num = (id) => Number($(id).value);

// ---- messages to the user ---------------------------------------------------

/** One message at a time: a new one replaces the one on screen (an error
 * stays until it is replaced, dismissed or times out; the same message
 * again only restarts its timer). */
function toast(text, kind = 'info', ms = kind === 'error' ? 9000 : 3500) {
  const box = $('toasts');
  const same = [...box.children].find((e) => e.textContent === text);
  const el = same ?? document.createElement('div');
  if (!same) {
    el.className = `toast ${kind}`;
    el.dataset.testid = kind === 'error' ? 'toast-error' : 'toast';
    el.textContent = text;
    el.title = 'Click to dismiss';
    el.onclick = () => el.remove();
    box.replaceChildren(el);
  }
  clearTimeout(el.timer);
  el.timer = setTimeout(() => el.remove(), ms);
}
// Anything unexpected still reaches the user as a message, never a dead page.
window.addEventListener('error', (e) => toast(`Unexpected error: ${e.message}`, 'error'));
window.addEventListener('unhandledrejection', (e) => toast(`Unexpected error: ${e.reason?.message || e.reason}`, 'error'));

// ---- state ------------------------------------------------------------------

const app = {
  state: null, // latest `state` message
  frame: null, // latest parsed frame (what is on screen)
  sel: { version: -1, faces: [], corners: [], edges: [] },
  tool: 'inflate',
  stroke: null,
  fitNext: true, // frame the camera on the next mesh frame
  workspace: null,
  lostConnection: false,
};

const hook = {
  get state() { return app.state; },
  get stats() { return app.state?.stats ?? null; },
  get version() { return app.state?.version ?? null; },
  get frameVersion() { return app.frame?.version ?? null; },
  get triangles() { return app.frame?.nt ?? 0; },
  get renders() { return viewer?.renders ?? 0; },
  get bbox() { return viewer?.bbox; },
  get stroking() { return !!app.stroke; },
  get strokeInfo() {
    const s = app.stroke;
    // In flight until the frame of every answered batch has come too.
    return s && { brush: s.brush, ending: s.ending, inflight: !!s.inflight || framesDue.length > 0, queued: !!(s.queued || s.queue?.length) };
  },
  get pending() { return [...conn.pending.values()].map((p) => p.op); },
  get selection() { return app.sel; },
  frames: 0,
  positionsOnlyFrames: 0,
  sparseFrames: 0,
  patchFrames: 0, // connectivity patches (remeshing strokes)
  previewFrames: 0,
  // Per stroke frame, in ms: pointer event → picture (strokeLatencies), and
  // its parts: waiting for the previous frame's answer (waitMs), request
  // sent → frame received (roundTripMs, includes the server's `ms`),
  // parse + apply + normals (clientMs), until the animation frame draws it
  // (toRenderMs) and the drawing itself (renderMs; real only with
  // `measureGpu`, which waits for the GPU with gl.finish after each stroke picture).
  strokeLatencies: [],
  waitMs: [],
  roundTripMs: [],
  clientMs: [],
  toRenderMs: [],
  renderMs: [],
  drawnTriangles: [], // triangles drawn for each stroke picture (fewer when partial)
  serverMs: [],
  measureGpu: false,
  lastFrameMs: null, // pointer event -> stroke frame rendered, last stroke frame
  lastParseRenderMs: null,
  errors: [],
  // The sculpt workspace (issue 19): what strokes sent, the mask shown.
  strokesSent: [], // stroke_begin fields
  framesSent: 0, // stroke frames (dabs) sent with stroke_frame requests
  batchSizes: [], // dabs per stroke_frame request (queued dabs go together)
  pressuresSent: [], // the pen pressure each stroke frame (dab) carried
  maskPaints: [], // mask_paint fields
  maskReplies: [], // `masked` of each mask request's answer
  sizing: null, // 'radius' or 'strength' while F sizes the brush
  get positions() { return app.frame ? Array.from(app.frame.positions) : null; },
  get sculptMask() { return viewer?.sculptMask ? Array.from(viewer.sculptMask) : null; },
  get maskedCount() { return viewer?.maskedCount ?? 0; },
  get camera() {
    if (!viewer) return null;
    const c = viewer.camera, t = viewer.controls?.target;
    return { ortho: viewer.ortho, position: c.position.toArray(), target: t ? t.toArray() : null, zoom: c.zoom, material: viewer.materialName };
  },
  setView: (dir) => viewer?.setView(dir),
  // For scenarios that select faces no click can reach (faces looking
  // into a ring of bodies): the selection as a pick would make it, and
  // the frame's arrays to find them by.
  selectFaces(faces) {
    app.sel = { version: app.frame?.version ?? -1, faces: [...faces], corners: [], edges: [] };
    applySelection();
  },
  get frameArrays() {
    const f = app.frame;
    return f && { positions: Array.from(f.positions), tris: Array.from(f.tris), triFace: Array.from(f.triFace), nf: f.nf };
  },
  project: (p) => viewer?.project(p),
  request: (op, fields) => conn.request(op, fields),
  get proxy() {
    return viewer && { triangles: viewer.proxy ? viewer.proxyTriangles : null, shown: !!viewer.proxyShown, buildMs: viewer.proxyMs, motion: [...viewer.motion], pixelRatio: viewer.renderer.getPixelRatio() };
  },
  setProxyEnabled(on) {
    viewer.useProxy = on;
    if (!on) viewer.disposeProxy();
  },
  benchOrbit,
  benchRender,
  comparePartialToFull,
  get partial() {
    return viewer && { enabled: viewer.partialEnabled, renders: viewer.partialRenders, triangles: viewer.partialTriangles, rect: viewer.lastPartialRect ?? null };
  },
  get viewer() { return viewer; }, // for experiments from the console
};
const pushCapped = (xs, x) => {
  xs.push(x);
  if (xs.length > 2000) xs.shift();
};
window.__holey = hook;

// ---- 3D view ----------------------------------------------------------------

let viewer = null;
const canvas = $('canvas');
try {
  viewer = new Viewer(canvas);
} catch (e) {
  const box = document.createElement('div');
  box.className = 'fatal';
  box.textContent = `The 3D view could not start (${e.message}). This browser or its graphics driver does not provide WebGL 2; the rest of the page still works.`;
  $('view').append(box);
}

// ---- connection -------------------------------------------------------------

const wsUrl = new URL('ws', location.href);
wsUrl.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
const conn = new Connection(wsUrl.href, {
  open() {
    $('connection').textContent = 'connected';
    $('connection').classList.remove('bad');
    if (app.lostConnection) toast('Reconnected to the server.');
    app.lostConnection = false;
    call('hello');
    loadPrimitives();
    loadRemeshSchemes();
  },
  close(delay) {
    const el = $('connection');
    el.textContent = `disconnected — retrying in ${Math.round(delay / 100) / 10} s`;
    el.classList.add('bad');
    if (!app.lostConnection) {
      toast(conn.everOpened ? 'Lost the connection to holey serve; trying to reconnect…' : 'Cannot reach holey serve; retrying…', 'error');
    }
    app.lostConnection = true;
    if (app.stroke) endStrokeLocally();
    hideProgress();
  },
  state: onState,
  frame: onFrame,
  progress: onProgress,
  notice: (t) => toast(t, 'error'),
});

/** Send a request; failures become a toast and resolve to null. */
async function call(op, fields = {}) {
  try {
    return await conn.request(op, fields);
  } catch (e) {
    if (e.cancelled) toast('Cancelled.');
    else toast(e.message, 'error');
    hook.errors.push({ op, message: e.message });
    return null;
  }
}

async function loadPrimitives() {
  const ok = await call('primitives');
  if (!ok?.primitives) return;
  const sel = $('primitive-select');
  const keep = sel.value;
  sel.replaceChildren(...ok.primitives.map((p) => {
    const o = document.createElement('option');
    o.value = p.spec;
    o.textContent = p.name;
    o.title = p.about || '';
    return o;
  }));
  if (keep && ok.primitives.some((p) => p.spec === keep)) sel.value = keep;
}

function statsText(s) {
  const genus = s.genus == null ? 'genus – (not a closed manifold)' : `genus ${s.genus}`;
  let t = `V ${s.vertices} · E ${s.edges} · F ${s.faces} · components ${s.components} · ${genus} · boundary loops ${s.boundary_loops}`;
  if (s.triangles != null) t += ` · ${s.triangles} triangles`;
  if (s.manifold === false) t += ' · non-manifold';
  return t;
}

function onState(s) {
  app.state = s;
  const body = document.body;
  body.classList.toggle('ws-model', s.workspace === 'model');
  body.classList.toggle('ws-sculpt', s.workspace === 'sculpt');
  body.classList.toggle('mode-rind', s.mode === 'rind');
  for (const b of document.querySelectorAll('[data-ws]')) b.classList.toggle('active', b.dataset.ws === s.workspace);
  $('undo').disabled = !s.can_undo;
  $('redo').disabled = !s.can_redo;
  if (s.stats) $('stats').textContent = statsText(s.stats);
  $('busy').textContent = s.busy ? `working: ${s.busy}…` : '';
  if (s.remesh && document.activeElement !== $('remesh-detail')) {
    $('remesh-detail').value = s.remesh.detail;
    $('remesh-value').textContent = s.remesh.detail > 0 ? s.remesh.detail : 'off';
  }
  if (s.workspace !== app.workspace) {
    // Polygons read best flat with their edges; sculpts smooth without.
    app.workspace = s.workspace;
    setShading(s.workspace === 'model', s.workspace === 'model' && (app.frame?.nt ?? 0) < 300000);
    if (s.workspace !== 'sculpt') viewer?.hideBrush();
    clearSelection();
  }
  updateBadge();
}

function onFrame(buf) {
  const t0 = performance.now();
  let f;
  const prev = app.frame;
  try {
    f = parseFrame(buf, prev);
  } catch (e) {
    if (buf.byteLength >= 12 && new DataView(buf).getUint32(8, true) & (FLAG_PATCH | FLAG_SPARSE)) {
      // A patch or sparse frame for a mesh this tab does not hold (it
      // missed a frame): ask for the whole mesh again, quietly.
      call('hello');
      return;
    }
    toast(`Could not read a mesh frame: ${e.message}`, 'error');
    return;
  }
  app.frame = f;
  hook.frames++;
  if (f.positionsOnly) hook.positionsOnlyFrames++;
  if (f.sparse) hook.sparseFrames++;
  if (f.patch) hook.patchFrames++;
  if (f.preview) hook.previewFrames++;
  if (!viewer) {
    if (f.sparse) applySparse(f.positions, f.sparseIdx, f.sparsePos);
    if (f.patch) applyPatch(f, { positions: prev.positions, tris: prev.tris, triFace: prev.triFace, edges: prev.edges });
    return;
  }
  let newTopology;
  try {
    newTopology = viewer.setFrame(f);
  } catch (e) {
    toast(`Could not show a mesh frame: ${e.message}`, 'error');
    call('hello'); // ask for a full frame again
    return;
  }
  if (!f.positionsOnly) showMaskCount();
  // A commit frame settles the bounds a stroke moved: the brush's size
  // is relative to them.
  if (isCommit(f)) showSliderValues();
  if (newTopology) {
    // Huge meshes: the wireframe would cost more than the surface itself.
    if (f.nt > 300000 && $('wireframe').checked) setShading(viewer.flat, false);
    if (f.preview || f.version === app.sel.version) applySelection();
    else clearSelection();
    showSliderValues(); // the brush radius is relative to the mesh size
  }
  if (app.fitNext) {
    app.fitNext = false;
    viewer.setView();
  }
  // setFrame asked for a picture at the next animation frame (only the part
  // of it that changed, during a stroke), together with whatever else
  // changed (the brush ring, a second frame): at most one per display frame.
  const applied = performance.now();
  hook.lastParseRenderMs = applied - t0;
  // A stroke frame comes right after its answer, by which time the next
  // batch may be in flight: it is the oldest batch answered and not yet
  // drawn.
  const inflight = framesDue.length ? framesDue.shift() : app.stroke?.inflight;
  if (inflight && !inflight.measured) {
    inflight.measured = true;
    // A batch of dabs shows in this one picture: each dab's latency runs
    // from its own pointer event.
    for (const d of inflight.batch ?? [inflight]) {
      pendingMeasures.push({ ev: d.t, sent: d.sent ?? d.t, recv: t0, applied });
    }
  }
  updateBadge();
}

// Stroke frames waiting for their picture (see hook.strokeLatencies).
const pendingMeasures = [];
// Batches of dabs answered whose frame has not come yet: the server
// answers a stroke_frame first and sends its frame right after, so that
// the next batch is computed while this tab reads and draws the frame.
const framesDue = [];
if (viewer) {
  viewer.afterRender = (start, end) => {
    if (!pendingMeasures.length) return;
    if (hook.measureGpu) {
      waitForGpu();
      end = performance.now();
    }
    for (const m of pendingMeasures) {
      hook.lastFrameMs = end - m.ev;
      pushCapped(hook.strokeLatencies, hook.lastFrameMs);
      pushCapped(hook.waitMs, m.sent - m.ev);
      pushCapped(hook.roundTripMs, m.recv - m.sent);
      pushCapped(hook.clientMs, m.applied - m.recv);
      pushCapped(hook.toRenderMs, start - m.applied);
      pushCapped(hook.renderMs, end - start);
      pushCapped(hook.drawnTriangles, viewer.lastRenderPartial ? viewer.partialTriangles : (app.frame?.nt ?? 0));
    }
    pendingMeasures.length = 0;
  };
}

function updateBadge() {
  const b = $('mode-badge');
  let text = '';
  if (app.state?.mode === 'rind') text = 'Rind: click a face to punch a hole, Shift-click to peel; Done keeps it';
  // Sculpt drag previews explain themselves (red = vanishes at release).
  else if (app.frame?.preview && app.state?.workspace === 'model') text = 'Preview — “Create handle” keeps it, “Discard” drops it';
  b.textContent = text;
  b.hidden = !text;
}

// ---- progress of long operations ------------------------------------------

function showProgress(stage, fraction) {
  const p = $('progress');
  p.hidden = false;
  $('progress-stage').textContent = stage || 'working…';
  p.classList.toggle('indeterminate', fraction == null);
  p.querySelector('.fill').style.width = fraction == null ? '' : `${Math.round(fraction * 100)}%`;
}
function hideProgress() {
  $('progress').hidden = true;
}
function onProgress(m) {
  showProgress(m.stage, m.fraction);
}
$('progress-cancel').onclick = () => call('cancel');

async function long(op, fields, label) {
  showProgress(label, null);
  try {
    return await call(op, fields);
  } finally {
    hideProgress();
  }
}

// ---- toolbar ----------------------------------------------------------------

for (const b of document.querySelectorAll('[data-ws]')) b.onclick = () => call('workspace', { workspace: b.dataset.ws });
$('undo').onclick = () => call('undo');
$('redo').onclick = () => call('redo');
$('view-reset').onclick = () => viewer?.setView();
$('wireframe').onchange = () => setShading(viewer?.flat, $('wireframe').checked);
$('flat').onchange = () => setShading($('flat').checked, $('wireframe').checked);

function setShading(flat, wire) {
  $('flat').checked = !!flat;
  $('wireframe').checked = !!wire;
  viewer?.setFlat(!!flat);
  viewer?.setWireframe(!!wire);
}

$('primitive-create').onclick = async () => {
  const spec = $('primitive-select').value;
  if (!spec) return;
  app.fitNext = true;
  if (!(await long('primitive', { spec }, `creating ${spec}`))) app.fitNext = false;
};

// Import: file picker or a file dropped anywhere on the page.
$('import').onclick = () => $('import-input').click();
$('import-input').onchange = () => {
  const file = $('import-input').files[0];
  $('import-input').value = ''; // picking the same file again must fire again
  if (file) importFile(file);
};

async function importFile(file) {
  showProgress(`opening ${file.name}`, null);
  app.fitNext = true;
  try {
    const res = await fetch(`api/import?name=${encodeURIComponent(file.name)}`, { method: 'POST', body: file });
    let body = null;
    try {
      body = await res.json();
    } catch {
      /* not JSON: reported below from the status */
    }
    if (!res.ok || !body?.ok) {
      app.fitNext = false;
      toast(`Could not open ${file.name}: ${body?.error || `${res.status} ${res.statusText}`}`, 'error');
    } else {
      toast(`Opened ${file.name}`);
    }
  } catch (e) {
    app.fitNext = false;
    toast(`Could not upload ${file.name}: ${e.message}`, 'error');
  } finally {
    hideProgress();
  }
}

let dragDepth = 0;
const dropHint = document.querySelector('.drop');
const hasFiles = (e) => [...(e.dataTransfer?.types || [])].includes('Files');
window.addEventListener('dragenter', (e) => {
  if (!hasFiles(e)) return;
  dragDepth++;
  dropHint.hidden = false;
});
window.addEventListener('dragleave', () => {
  if (--dragDepth <= 0) { dragDepth = 0; dropHint.hidden = true; }
});
window.addEventListener('dragover', (e) => {
  if (hasFiles(e)) e.preventDefault();
});
window.addEventListener('drop', (e) => {
  e.preventDefault();
  dragDepth = 0;
  dropHint.hidden = true;
  const file = e.dataTransfer?.files?.[0];
  if (file) importFile(file);
});

$('export').onclick = async () => {
  const format = $('export-format').value;
  try {
    const res = await fetch(`api/export?format=${format}`);
    if (!res.ok) {
      let msg = `${res.status} ${res.statusText}`;
      try { msg = (await res.json()).error || msg; } catch { /* keep status */ }
      throw new Error(msg);
    }
    const name = /filename="([^"]+)"/.exec(res.headers.get('Content-Disposition') || '')?.[1] || `holey.${format}`;
    const url = URL.createObjectURL(await res.blob());
    const a = document.createElement('a');
    a.href = url;
    a.download = name;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 60000);
  } catch (e) {
    toast(`Export failed: ${e.message}`, 'error');
  }
};

window.addEventListener('keydown', (e) => {
  const t = e.target;
  if (t instanceof HTMLInputElement && t.type !== 'range' && t.type !== 'checkbox' && t.type !== 'radio') return;
  if (t instanceof HTMLSelectElement) return;
  const mod = e.ctrlKey || e.metaKey;
  const k = e.key.toLowerCase();
  const sculpt = app.state?.workspace === 'sculpt';
  if (sizing) {
    e.preventDefault();
    if (k === 'escape') finishSizing(true);
    else if (k === 'enter' || k === 'f') finishSizing(false);
    return;
  }
  // The numpad views, as in Blender: 1 front, 3 side, 7 top (Ctrl: the
  // opposite side), 5 orthographic, . frame.
  const views = { Numpad1: 'front', Numpad3: 'side', Numpad7: 'top' };
  if (views[e.code]) {
    e.preventDefault();
    axisView(views[e.code], mod);
  } else if (e.code === 'Numpad5') {
    e.preventDefault();
    toggleOrtho();
  } else if (e.code === 'NumpadDecimal' || (!mod && k === 'home')) {
    e.preventDefault(); // a focused slider would jump to its minimum
    viewer?.setView();
  } else if (mod && k === 'z') {
    e.preventDefault();
    if (!app.stroke) call(e.shiftKey ? 'redo' : 'undo');
  } else if (mod && k === 'y') {
    e.preventDefault();
    if (!app.stroke) call('redo');
  } else if (!mod && k === 'f') {
    // Sculpt: F sizes the radius on screen, Shift+F the strength (Blender,
    // SculptGL); elsewhere, and always with Home, it frames the mesh.
    if (sculpt) startSizing(e.shiftKey ? 'strength' : 'radius');
    else viewer?.setView();
  } else if (!mod && sculpt && (e.code === 'BracketLeft' || e.code === 'BracketRight')) {
    e.preventDefault();
    stepBrush(e.code === 'BracketRight', e.shiftKey);
  } else if (!mod && k === 'escape') {
    clearSelection();
  } else if (sculpt && e.altKey && !mod && e.code === 'KeyM') {
    e.preventDefault(); // Blender: Alt+M clears the mask, Ctrl+I inverts it
    if (!app.stroke) maskOp('mask_clear');
  } else if (sculpt && mod && !e.altKey && e.code === 'KeyI') {
    e.preventDefault();
    if (!app.stroke) maskOp('mask_invert');
  } else if (!mod && !e.altKey && sculpt && /^Digit[0-9]$/.test(e.code)) {
    // 1 … 9 and 0 pick the first ten brushes, Shift+1 … the rest (Blender).
    const tool = (e.shiftKey ? SHIFT_NUMBER_KEYS : NUMBER_KEYS)[(Number(e.code.slice(5)) + 9) % 10];
    if (tool) setTool(tool);
  } else if (!mod && !e.altKey && sculpt && LETTER_KEYS[(e.shiftKey ? 'Shift+' : '') + e.code]) {
    setTool(LETTER_KEYS[(e.shiftKey ? 'Shift+' : '') + e.code]);
  }
});

// ---- model workspace: selection and operations ------------------------------

function clearSelection() {
  app.sel = { version: app.frame?.version ?? -1, faces: [], corners: [], edges: [] };
  applySelection();
}

function applySelection() {
  const s = app.sel;
  // Highlights are drawn on the committed mesh only, not on a preview.
  viewer?.setSelection(app.frame?.preview ? {} : s);
  const parts = [];
  // Long lists (a loop, an inverted selection) are counted, not listed.
  const list = (what, xs) => (xs.length > 12 ? `${xs.length} ${what}s` : `${what}${xs.length > 1 ? 's' : ''} ${xs.join(', ')}`);
  if (s.faces.length) parts.push(list('face', s.faces));
  if (s.corners.length) parts.push(list('corner', s.corners.map(([f, v]) => `${v}@${f}`)));
  if (s.edges.length) parts.push(list('edge', s.edges));
  $('selection').textContent = parts.length ? parts.join(' · ') : 'nothing selected';
}

function pickMode(e) {
  if (e.shiftKey || e.altKey) return 'corner';
  return document.querySelector('[name=pick]:checked').value;
}

async function modelClick(e) {
  if (!viewer || !app.frame) return;
  const hit = viewer.pick(e.clientX, e.clientY);
  if (app.state?.mode === 'rind') {
    if (hit) await call('rind_punch', { version: app.frame.version, face: hit.face, peel: e.shiftKey });
    return;
  }
  if (app.frame.preview) return; // indices of a preview are not the document's
  if (app.sel.version !== app.frame.version) clearSelection();
  const s = app.sel;
  if (!hit) {
    clearSelection();
    return;
  }
  const mode = pickMode(e);
  if (mode === 'face') {
    const i = s.faces.indexOf(hit.face);
    if (i >= 0) s.faces.splice(i, 1);
    else s.faces.push(hit.face);
  } else if (mode === 'corner') {
    const v = viewer.nearestVertex(viewer.faceVertices(hit.face), hit.point);
    const i = s.corners.findIndex(([f, w]) => f === hit.face && w === v);
    if (i >= 0) s.corners.splice(i, 1);
    else s.corners.push([hit.face, v]);
  } else {
    const ed = viewer.nearestEdge(hit.face, hit.point);
    if (ed >= 0) {
      const i = s.edges.indexOf(ed);
      if (i >= 0) s.edges.splice(i, 1);
      else s.edges.push(ed);
    }
  }
  applySelection();
}

$('op-insert-edge').onclick = () => {
  const c = app.sel.corners;
  if (c.length < 2) return toast('Select two corners of one face first (Corners mode, or Shift-click near a vertex).', 'error');
  const [a, b] = c.slice(-2);
  if (a[0] !== b[0]) return toast('The two corners must belong to the same face.', 'error');
  call('insert_edge', { version: app.frame.version, corners: [a, b] });
};
$('op-delete-edge').onclick = () => {
  const edges = app.sel.edges;
  if (!edges.length) return toast('Select an edge first (Edges mode, click next to it).', 'error');
  call('delete_edge', { version: app.frame.version, edge: edges[edges.length - 1] });
};

function handleFields(preview) {
  const f = app.sel.faces;
  if (f.length !== 2 && f.length < 4) {
    toast('Select two faces for a handle, or four or more to join them through a hub.', 'error');
    return null;
  }
  const fields = {
    version: app.sel.version, faces: f, segments: num('handle-segments'),
    w1: num('handle-w1'), w2: num('handle-w2'), curve: $('handle-curve').value, preview,
  };
  // Four or more faces: a multi-face handle, which starts at each face's
  // first corner; its hub's size is the one setting of its own.
  if (f.length >= 4) return { ...fields, hub_scale: num('handle-hub-scale') };
  // A corner picked on each face fixes the twist of the handle.
  const ca = app.sel.corners.find(([face]) => face === f[0]);
  const cb = app.sel.corners.find(([face]) => face === f[1]);
  if (ca && cb) fields.corners = [ca[1], cb[1]];
  return fields;
}
$('op-handle').onclick = () => {
  const f = handleFields(true);
  if (f) long('handle', f, 'previewing handle');
};
$('handle-commit').onclick = async () => {
  const f = handleFields(false);
  if (!f) return;
  // The answer says which curve and how the genus changed.
  const ok = await long('handle', f, f.faces.length > 2 ? 'making multi-face handle' : 'making handle');
  if (ok?.message) toast(ok.message);
};
$('handle-discard').onclick = () => call('hello'); // re-sends the committed mesh

$('op-rind').onclick = () => long('rind_begin', { thickness: num('rind-thickness') }, 'making the rind');
$('rind-done').onclick = () => call('rind_end', { commit: true });
$('rind-cancel').onclick = () => call('rind_end', { commit: false });
$('op-sierpinski').onclick = () => long('sierpinski', { level: num('sierpinski-level') }, 'Sierpinski');
$('op-menger').onclick = () =>
  long('menger', { level: num('menger-level'), exact: $('menger-exact').checked }, 'Menger');
$('op-subdivide').onclick = () =>
  long('subdivide', { scheme: $('subdivide-scheme').value, levels: num('subdivide-levels') }, 'subdividing');

// ---- TopMod's toolbox: selection tools, remeshing, extrusion, cuts, wireframe ---

/** The selection as request fields, display indices of the picture shown
 * (corners stand for their vertices). */
function selectionFields() {
  const s = app.sel;
  if (s.version !== app.frame?.version) return { version: app.frame?.version, faces: [], edges: [], vertices: [] };
  return { version: s.version, faces: [...s.faces], edges: [...s.edges], vertices: [...new Set(s.corners.map(([, v]) => v))] };
}

/** The faces or edges an answer names become the selection (of the
 * version the answer names: a new mesh's frame may still be on its way,
 * and onFrame shows the selection when it comes). */
function selectFromReply(ok) {
  if (!ok || (!ok.faces && !ok.edges)) return;
  app.sel = { version: ok.version ?? app.frame?.version ?? -1, faces: ok.faces ?? [], corners: [], edges: ok.edges ?? [] };
  if (app.frame?.version === app.sel.version) applySelection();
}

for (const b of document.querySelectorAll('[data-query]')) {
  b.onclick = async () => {
    const s = selectionFields();
    const ok = await call('select', { query: b.dataset.query, version: s.version, faces: s.faces, edges: s.edges });
    selectFromReply(ok);
  };
}

// Remesh: the schemes and their parameters come from the server.
const remeshing = { schemes: [] };

async function loadRemeshSchemes() {
  const ok = await call('remesh_schemes');
  if (!ok?.schemes) return;
  remeshing.schemes = ok.schemes;
  const sel = $('remesh-scheme');
  const keep = sel.value;
  sel.replaceChildren(...ok.schemes.map((s) => {
    const o = document.createElement('option');
    o.value = s.name;
    o.textContent = s.title;
    o.title = s.closed_only ? `${s.name}: closed surfaces only` : s.name;
    return o;
  }));
  if (keep && ok.schemes.some((s) => s.name === keep)) sel.value = keep;
  if (ok.max_levels) $('remesh-levels').max = ok.max_levels;
  showRemeshParams();
}

function showRemeshParams() {
  const scheme = remeshing.schemes.find((s) => s.name === $('remesh-scheme').value);
  const params = scheme?.params ?? [];
  const box = $('remesh-params');
  box.replaceChildren(...params.map((p) => {
    const label = document.createElement('label');
    label.title = p.name;
    const input = document.createElement('input');
    input.dataset.testid = `remesh-param-${p.name}`;
    input.dataset.param = p.name;
    if (p.type === 'bool') {
      input.type = 'checkbox';
      input.checked = !!p.default;
      label.className = 'check';
      label.append(input, ` ${p.label}`);
    } else {
      input.type = 'number';
      input.step = '0.01';
      input.value = String(p.default);
      if (p.min != null) input.min = String(p.min);
      if (p.max != null) input.max = String(p.max);
      label.append(`${p.label} `, input);
    }
    return label;
  }));
  box.hidden = !params.length;
  $('remesh-note').textContent = scheme?.closed_only ? 'closed surfaces only' : '';
}
$('remesh-scheme').onchange = showRemeshParams;

$('op-remesh').onclick = () => {
  const scheme = $('remesh-scheme').value;
  if (!scheme) return toast('The remeshing schemes have not arrived from the server yet.', 'error');
  const params = {};
  for (const input of $('remesh-params').querySelectorAll('input[data-param]')) {
    params[input.dataset.param] = input.type === 'checkbox' ? input.checked : Number(input.value);
  }
  const title = $('remesh-scheme').selectedOptions[0]?.textContent || scheme;
  long('remesh', { scheme, levels: num('remesh-levels'), params }, `remeshing: ${title}`);
};

// Extrude: the inputs each kind reads.
const EXTRUDE_INPUTS = {
  plain: ['distance', 'scale', 'rotation', 'count'],
  together: ['distance', 'count', 'direction'],
  'doo-sabin': ['distance', 'scale', 'twist', 'count'],
  cubical: ['height', 'count'],
  dodecahedral: ['height'],
  icosahedral: ['height'],
  octahedral: ['height'],
  stellate: ['distance'],
  'double-stellate': ['distance'],
  dome: ['height', 'count'],
};
function showExtrudeInputs() {
  const kind = $('extrude-kind').value;
  const use = EXTRUDE_INPUTS[kind] ?? [];
  for (const l of document.querySelectorAll('[data-for]')) l.hidden = !use.includes(l.dataset.for);
  // A dome's count is its rings: TopMod's half sphere has five.
  if (kind === 'dome' && num('extrude-count') === 1) $('extrude-count').value = '5';
}
$('extrude-kind').onchange = showExtrudeInputs;
showExtrudeInputs();

$('op-extrude').onclick = async () => {
  const s = selectionFields();
  if (!s.faces.length) return toast('Select the faces to extrude first (Faces mode).', 'error');
  const kind = $('extrude-kind').value;
  const fields = { version: s.version, faces: s.faces, kind };
  for (const k of EXTRUDE_INPUTS[kind] ?? []) fields[k] = k === 'direction' ? $('extrude-direction').value : num(`extrude-${k}`);
  const ok = await call('extrude', fields);
  if (ok?.message) toast(ok.message);
  selectFromReply(ok); // the new tops, ready to extrude again
};

async function cutOp(op, fields, all = false) {
  const s = selectionFields();
  if (!all && !s.faces.length && !s.edges.length && !s.vertices.length) {
    return toast(`Select what to ${op} first: corners (for their vertices), edges or faces.`, 'error');
  }
  const ok = await call(op, all ? { all: true, ...fields } : { ...s, ...fields });
  if (ok?.message) toast(ok.message);
  selectFromReply(ok); // the new faces
}
$('op-cut').onclick = () => cutOp('cut', { distance: num('cut-distance') });
$('op-truncate').onclick = () => cutOp('truncate', { fraction: num('truncate-fraction') });
$('op-truncate-all').onclick = () => cutOp('truncate', { fraction: num('truncate-fraction') }, true);

// The hulls act on the whole mesh: no selection. The hull has the mesh's
// bounding box; the dual hull is larger (a cube's is an octahedron three
// times as wide), so the view frames it.
async function hullOp(dual) {
  app.fitNext = dual;
  const ok = await long('hull', { dual }, dual ? 'dual convex hull' : 'convex hull');
  if (!ok) app.fitNext = false;
  if (ok?.message) toast(ok.message);
}
$('op-hull').onclick = () => hullOp(false);
$('op-dual-hull').onclick = () => hullOp(true);

$('op-wireframe').onclick = () => long('wireframe', { thickness: num('wireframe-thickness') }, 'wireframe');
$('op-columns').onclick = () =>
  long('wireframe', { thickness: num('wireframe-thickness'), columns: num('columns-sides') }, 'columns');

for (const b of document.querySelectorAll('[data-tool-op]')) {
  b.onclick = async () => {
    const s = selectionFields();
    const ok = await long('tool', { tool: b.dataset.toolOp, version: s.version, faces: s.faces, vertices: s.vertices }, b.textContent);
    if (ok?.message) toast(ok.message);
  };
}

// ---- sculpt workspace ---------------------------------------------------------

/** The brushes that follow the pointer: the strength slider does not apply. */
const DRAGS = new Set(['grab', 'move', 'move-piece', 'snake_hook']);
/** The number keys' brushes (1 … 9, then 0), as the buttons' titles say;
 * with Shift, the brushes past ten, as Blender numbers its brushes. */
const NUMBER_KEYS = ['inflate', 'smooth', 'grab', 'move', 'move-piece', 'snake_hook', 'draw', 'clay', 'crease', 'flatten'];
const SHIFT_NUMBER_KEYS = ['layer', 'pinch', 'scrape', 'scale'];
/** Blender's sculpt-mode letters (by physical key, as `e.code` names it). */
const LETTER_KEYS = {
  KeyX: 'draw', KeyC: 'clay', 'Shift+KeyC': 'crease', KeyI: 'inflate', KeyS: 'smooth', KeyG: 'grab',
  KeyK: 'snake_hook', KeyL: 'layer', KeyP: 'pinch', 'Shift+KeyT': 'flatten', KeyM: 'mask',
};

/** Each brush's own strength, as in Blender and SculptGL: the slider shows
 * the chosen brush's, and choosing another brings that one's back (the
 * page's default until it is changed). Radius is shared, as Blender's
 * unified size is by default. */
const brushStrengths = {};
const DEFAULT_STRENGTH = Number($('strength').defaultValue);
const hasStrength = (tool) => !DRAGS.has(tool) && tool !== 'mask';
/** The strength `tool` strokes with: the slider's for the chosen brush. */
const strengthOf = (tool) => (tool === app.tool ? num('strength') : brushStrengths[tool] ?? DEFAULT_STRENGTH);

function setTool(tool) {
  if (app.tool && hasStrength(app.tool)) brushStrengths[app.tool] = num('strength');
  if (hasStrength(tool)) {
    $('strength').value = String(brushStrengths[tool] ?? DEFAULT_STRENGTH);
    $('strength-value').textContent = num('strength').toFixed(2);
  }
  app.tool = tool;
  for (const b of document.querySelectorAll('[data-tool]')) b.classList.toggle('active', b.dataset.tool === tool);
  $('strength').disabled = DRAGS.has(tool) || tool === 'mask';
  $('strength').title = $('strength').disabled
    ? 'This brush follows the pointer: it has no strength'
    : 'Shift+[ and Shift+] change it; Shift+F then move the pointer sizes it';
}
for (const b of document.querySelectorAll('[data-tool]')) b.onclick = () => setTool(b.dataset.tool);
setTool('inflate');

const brushRadius = () => (num('radius') / 100) * (viewer?.bbox.diag ?? 1);
function showSliderValues() {
  $('radius-value').textContent = `${num('radius')}% (${brushRadius().toPrecision(3)})`;
  $('strength-value').textContent = num('strength').toFixed(2);
  $('lazy-value').textContent = num('lazy-mouse') > 0 ? `${num('lazy-mouse')} px` : 'off';
}
/** Set a slider (clamped and snapped to its step by the browser). */
function setSlider(id, value) {
  $(id).value = String(value);
  showSliderValues();
}
$('radius').oninput = showSliderValues;
$('strength').oninput = showSliderValues;
$('lazy-mouse').oninput = showSliderValues;
showSliderValues();
$('remesh-detail').oninput = () => {
  $('remesh-value').textContent = num('remesh-detail') > 0 ? num('remesh-detail') : 'off';
};
$('remesh-detail').onchange = () => call('set_remesh', { detail: num('remesh-detail') });
$('falloff-select').onchange = () => {
  $('falloff-custom').hidden = $('falloff-select').value !== 'custom';
};

// Masking: the mask lives on the server (every stroke respects it); the
// frames carry it and the viewer darkens what is masked.
async function maskOp(op, fields = {}) {
  const ok = await call(op, fields);
  if (ok) hook.maskReplies.push(ok.masked);
  return ok;
}
$('mask-clear').onclick = () => maskOp('mask_clear');
$('mask-invert').onclick = () => maskOp('mask_invert');
function showMaskCount() {
  const n = viewer?.maskedCount ?? 0;
  $('mask-count').textContent = n ? `${n} vertices masked` : '';
}

// ---- display ------------------------------------------------------------------

$('matcap-select').onchange = () => viewer?.setMaterial($('matcap-select').value);
$('ortho-toggle').onchange = () => viewer?.setOrtho($('ortho-toggle').checked);
/** The axis views (Blender's numpad 1, 3 and 7): `dir` points from the
 * mesh to the camera; top is seen with −z up the screen. */
const AXIS_VIEWS = { front: [0, 0, 1], side: [1, 0, 0], top: [0, 1, 1e-6] };
function axisView(name, opposite = false) {
  const d = AXIS_VIEWS[name];
  viewer?.setView(opposite ? d.map((x) => -x) : d);
}
for (const name of Object.keys(AXIS_VIEWS)) $(`view-${name}`).onclick = () => axisView(name);
function toggleOrtho() {
  $('ortho-toggle').checked = !$('ortho-toggle').checked;
  viewer?.setOrtho($('ortho-toggle').checked);
}

$('screenshot').onclick = () => {
  if (!viewer) return toast('There is no 3D view to take a picture of.', 'error');
  const url = viewer.screenshot();
  const stamp = new Date().toISOString().replace(/[:.]/g, '-').slice(0, 19);
  const a = document.createElement('a');
  a.href = url;
  a.download = `holey-${stamp}.png`;
  document.body.append(a);
  a.click();
  a.remove();
};

// ---- repairs ------------------------------------------------------------------

async function repair(op, fields) {
  const ok = await call(op, fields);
  if (ok?.message) toast(ok.message);
}
$('op-weld').onclick = () => repair('weld', { distance: num('weld-distance') / 100 });
$('op-make-manifold').onclick = () => repair('make_manifold');

// ---- strokes ------------------------------------------------------------------

/** Stroke protocol: stroke_begin, then stroke_frame with at most one request
 * in flight (the dabs waiting in `queue`, sent together up to MAX_BATCH
 * when the answer comes; the server answers before it sends the frame, so
 * the next batch is computed while this tab draws), then stroke_end once
 * everything sent has been answered. */
/** Inflate, draw, clay and crease: displacement per frame at full strength,
 * as a share of the radius (the server's strength is in world units). */
const INFLATE_PER_FRAME = 0.05;
/** Crease at full strength, per frame: its groove is narrower than the
 * brush (the weight squared), so it needs twice the depth to read on the
 * bunny at the default strength. */
const CREASE_PER_FRAME = 0.1;
/** Pinch at full strength: the share of the way to the centre per frame. */
const PINCH_PER_FRAME = 0.25;
/** Local scale at full strength: the growth per frame (0.05 barely
 * showed on the bunny at the default strength along a stroke). */
const SCALE_PER_FRAME = 0.1;
/** Layer at full strength: the slab's height, as a share of the radius
 * (the server moves at most half of it a frame, and takes at most a
 * quarter). At the default strength, an eighth of the radius: a tenth
 * read as nothing on the bunny's scanned bumps. */
const LAYER_PER_RADIUS = 0.25;
/** Shift+F: pixels from the anchor for strength 1. */
const STRENGTH_PX = 200;
/** The most dabs one pointer event adds (a jump across the screen with a
 * tiny spacing), and the most waiting for the server: past it every other
 * one is dropped, so a slow frame (a collision, a huge mesh) leaves the
 * brush at most that many frames behind the pointer. */
const MAX_DABS_PER_EVENT = 400;
const MAX_QUEUE = 64;
/** The most queued dabs one stroke_frame request carries. */
const MAX_BATCH = 8;

/** The strength the server takes for `brush`: world units per frame for
 * the displacing brushes (scaled to the radius, as inflate always was; for
 * layer, the slab's height),
 * shares for the others; `sign` −1 inverts where that means something. */
function strokeStrength(brush, radius, s, sign) {
  switch (brush) {
    case 'inflate': case 'draw': case 'clay':
      return s * INFLATE_PER_FRAME * radius * sign;
    case 'crease':
      return s * CREASE_PER_FRAME * radius * sign;
    case 'smooth': case 'flatten': case 'scrape':
      return s; // a share of the way in [0, 1]: no opposite
    case 'layer':
      return s * LAYER_PER_RADIUS * radius * sign; // negative sinks
    case 'pinch':
      return s * PINCH_PER_FRAME * sign; // negative spreads
    case 'scale':
      return s * SCALE_PER_FRAME * sign; // negative shrinks
    default:
      return 1; // grab, move and the snake hook follow the pointer
  }
}

/** Falloff, symmetry and what pen pressure drives, for stroke_begin. */
function strokeOptions() {
  const o = {};
  const f = $('falloff-select').value;
  o.falloff = f === 'custom' ? { custom: [0, 1, 2, 3, 4].map((i) => num(`falloff-custom-${i}`)) } : f;
  const axes = ['x', 'y', 'z'].filter((a) => $(`symmetry-${a}`).checked).join('');
  if (axes) {
    o.symmetry = axes;
    o.symmetry_about = $('symmetry-about').value;
  }
  const drives = $('pressure-drives').value;
  if (drives !== 'none') o.pressure_drives = drives;
  return o;
}

/** The pen's pressure for this event, or undefined (a mouse, or pressure
 * switched off). */
function penPressure(stroke, e) {
  return stroke.pen && e.pointerType === 'pen' && $('pressure-drives').value !== 'none' ? e.pressure : undefined;
}

function newStroke(brush, hit, e, radius) {
  return {
    brush,
    anchor: hit.point,
    normal: hit.normal,
    radius,
    inflight: null,
    queue: [],
    ending: false,
    pointerId: e.pointerId,
    pen: e.pointerType === 'pen',
    last: hit.point, // the last dab's centre
    lazy: [e.clientX, e.clientY], // the stabilizer's end of the string
  };
}

function beginStroke(hit, e, override = null) {
  const sign = $('deflate').checked !== e.ctrlKey ? -1 : 1;
  const tool = override ?? app.tool;
  // "Move piece" is the move brush without a radius: the whole piece.
  const piece = tool === 'move-piece';
  const brush = piece ? 'move' : tool;
  const stroke = newStroke(brush, hit, e, piece ? 0 : brushRadius());
  stroke.inflight = { t: e.timeStamp, measured: true };
  app.stroke = stroke;
  viewer.beginMotion('stroke'); // cheaper pictures until the stroke ends
  viewer.showBrush(hit.point, hit.normal, stroke.radius);
  const fields = {
    brush, radius: stroke.radius, strength: strokeStrength(brush, stroke.radius, strengthOf(tool), sign),
    point: hit.point, ...strokeOptions(),
  };
  const pressure = penPressure(stroke, e);
  if (pressure !== undefined) fields.pressure = pressure;
  pushCapped(hook.strokesSent, fields);
  conn.request('stroke_begin', fields).then(
    () => strokeAnswered(stroke),
    (err) => {
      toast(err.message, 'error');
      if (app.stroke === stroke) endStrokeLocally();
    },
  );
}

/** The mask brush: dabs are shown here at once and sent in one
 * `mask_paint` at release (Ctrl, or Invert, unmasks). */
function beginMaskStroke(hit, e) {
  const stroke = newStroke('mask', hit, e, brushRadius());
  stroke.erase = $('deflate').checked !== e.ctrlKey;
  stroke.points = [hit.point];
  app.stroke = stroke;
  viewer.paintMask(hit.point, stroke.radius, stroke.erase);
  viewer.showBrush(hit.point, hit.normal, stroke.radius);
}

function strokeAnswered(stroke) {
  stroke.inflight = null;
  if (app.stroke !== stroke) return;
  if (stroke.brush === 'mask') {
    if (!stroke.ending) return;
    stroke.inflight = { t: performance.now(), measured: true };
    const fields = { points: stroke.points, radius: stroke.radius, erase: stroke.erase };
    hook.maskPaints.push(fields);
    maskOp('mask_paint', fields).finally(() => {
      if (app.stroke === stroke) endStrokeLocally();
      viewer?.hideBrush();
      showMaskCount();
    });
    return;
  }
  if (stroke.queue.length) {
    // The dabs that piled up while the last request was answered go
    // together (at most MAX_BATCH): one frame each on the server, in
    // order, and one picture of the last here.
    const batch = stroke.queue.splice(0, MAX_BATCH);
    const sent = performance.now();
    for (const q of batch) q.sent = sent;
    stroke.inflight = { batch, t: batch[0].t, sent };
    const [q, ...rest] = batch;
    const fields = { point: q.point };
    if (q.pressure !== undefined) fields.pressure = q.pressure;
    if (rest.length) {
      fields.points = rest.map((r) => r.point);
      if (rest.some((r) => r.pressure !== undefined)) fields.pressures = rest.map((r) => r.pressure ?? 1);
    }
    hook.framesSent += batch.length;
    pushCapped(hook.batchSizes, batch.length);
    for (const r of batch) if (r.pressure !== undefined) pushCapped(hook.pressuresSent, r.pressure);
    const answered = stroke.inflight;
    conn.request('stroke_frame', fields).then(
      (ok) => {
        if (ok.ms != null) pushCapped(hook.serverMs, ok.ms);
        framesDue.push(answered); // its frame comes next
        strokeAnswered(stroke);
      },
      (err) => {
        toast(err.message, 'error');
        strokeAnswered(stroke);
      },
    );
  } else if (stroke.ending) {
    app.stroke = null;
    viewer.endMotion('stroke'); // full resolution again
    viewer.hideBrush(); // back on the surface with the next hover
    call('stroke_end').then((ok) => {
      // A drag whose release would have torn the surface is undone.
      if (ok?.message) toast(ok.message);
    });
  }
}

/** Where the brush is for a pointer event after the stabilizer (lazy
 * mouse): it trails the pointer on a string `lazy-mouse` pixels long and
 * moves only when the pointer pulls the string taut; null until then. */
function stabilized(s, e) {
  const L = num('lazy-mouse');
  if (!(L > 0)) return [e.clientX, e.clientY];
  const dx = e.clientX - s.lazy[0], dy = e.clientY - s.lazy[1], d = Math.hypot(dx, dy);
  if (d <= L) return null;
  s.lazy = [e.clientX - (dx / d) * L, e.clientY - (dy / d) * L];
  return s.lazy;
}

/** Dab centres from the last dab towards `point`, one every `spacing` % of
 * the radius, each put back on the surface under it when `onSurface`; what
 * is left over waits for the next event. So a fast drag lays as many dabs
 * as a slow one. */
function dabsTowards(s, point, onSurface) {
  const step = Math.max(1e-12, (num('stroke-spacing') / 100) * (s.radius || brushRadius()));
  const from = s.last;
  const d = Math.hypot(point[0] - from[0], point[1] - from[1], point[2] - from[2]);
  const n = Math.min(Math.floor(d / step), MAX_DABS_PER_EVENT);
  const out = [];
  for (let i = 1; i <= n; i++) {
    const t = (i * step) / d;
    let q = [from[0] + (point[0] - from[0]) * t, from[1] + (point[1] - from[1]) * t, from[2] + (point[2] - from[2]) * t];
    if (onSurface && i < n) {
      const [x, y] = viewer.project(q);
      const hit = viewer.pick(x, y);
      if (hit) q = hit.point;
    }
    out.push(q);
  }
  if (out.length) s.last = out[out.length - 1];
  return out;
}

function strokeMove(e) {
  const s = app.stroke;
  const at = stabilized(s, e);
  if (!at) return;
  const [x, y] = at;
  let point, normal = s.normal;
  // Grab, move and the snake hook follow the pointer in the view plane
  // through the picked point (the snake hook pulls off the surface).
  if (s.brush === 'grab' || s.brush === 'move' || s.brush === 'snake_hook') {
    point = viewer.planePoint(x, y, s.anchor);
  } else {
    const hit = viewer.pick(x, y);
    if (hit) ({ point, normal } = hit);
  }
  if (!point) return;
  viewer.showBrush(point, normal, s.radius || brushRadius());
  const pressure = penPressure(s, e);
  if (s.brush === 'grab' || s.brush === 'move') {
    // A drag goes where the pointer is: only the newest position matters.
    s.queue = [{ point, t: e.timeStamp, pressure }];
  } else {
    const dabs = dabsTowards(s, point, s.brush !== 'snake_hook');
    if (s.brush === 'mask') {
      for (const q of dabs) {
        s.points.push(q);
        viewer.paintMask(q, s.radius, s.erase);
      }
      return;
    }
    for (const q of dabs) s.queue.push({ point: q, t: e.timeStamp, pressure });
    if (s.queue.length > MAX_QUEUE) s.queue = s.queue.filter((_, i) => i % 2 === 1);
  }
  if (!s.inflight) strokeAnswered(s);
}

function strokeUp() {
  const s = app.stroke;
  if (!s || s.ending) return;
  s.ending = true;
  if (viewer.controls) viewer.controls.enabled = true;
  if (!s.inflight) strokeAnswered(s);
}

/** The connection dropped or the server refused: forget the stroke here. */
function endStrokeLocally() {
  app.stroke = null;
  framesDue.length = 0;
  viewer?.endMotion('stroke');
  if (viewer?.controls) viewer.controls.enabled = true;
}

// ---- sizing the brush on screen (F, Shift+F) -----------------------------------
// As in Blender: F shows the brush ring with the pointer on its rim; moving
// the pointer sizes it; a click, Enter or F again keeps it, Escape or a
// right click puts it back.

let sizing = null;
let lastPointer = null; // the pointer over the canvas (client pixels)

function startSizing(what) {
  if (!viewer || !app.frame || app.stroke || sizing) return;
  const r = canvas.getBoundingClientRect();
  const at = lastPointer ?? [r.left + r.width / 2, r.top + r.height / 2];
  const under = viewer.pick(at[0], at[1]);
  const through = under?.point ?? viewer.bbox.center;
  const ppu = viewer.pixelsPerUnit(through);
  const now = what === 'radius' ? brushRadius() * ppu : num('strength') * STRENGTH_PX;
  const anchor = [at[0] - now, at[1]];
  // The ring sits on the surface under the anchor (or in the view plane).
  const hit = viewer.pick(anchor[0], anchor[1]);
  const centre = hit?.point ?? viewer.planePoint(anchor[0], anchor[1], through) ?? through;
  const normal = hit?.normal ?? viewer.towardsCamera();
  sizing = { what, anchor, centre, normal, ppu, before: $(what).value };
  hook.sizing = what;
  updateSizing(at[0], at[1]);
}

function updateSizing(x, y) {
  const s = sizing;
  const d = Math.hypot(x - s.anchor[0], y - s.anchor[1]);
  if (s.what === 'radius') setSlider('radius', (d / s.ppu / viewer.bbox.diag) * 100);
  else setSlider('strength', d / STRENGTH_PX);
  const shown = s.what === 'radius' ? brushRadius() : (num('strength') * STRENGTH_PX) / s.ppu;
  viewer.showBrush(s.centre, s.normal, shown);
}

function finishSizing(cancel) {
  if (cancel) $(sizing.what).value = sizing.before;
  sizing = null;
  hook.sizing = null;
  showSliderValues();
  viewer?.hideBrush();
}

/** `[` and `]` (with Shift: strength), as in Blender and SculptGL. */
function stepBrush(up, strength) {
  if (strength) {
    setSlider('strength', Math.round((num('strength') + (up ? 0.05 : -0.05)) * 100) / 100);
  } else {
    const v = num('radius');
    setSlider('radius', up ? Math.max(v * 1.15, v + 0.5) : Math.min(v / 1.15, v - 0.5));
  }
}

// ---- pointer input on the canvas ----------------------------------------------
// Registered before OrbitControls so a stroke can switch them off before
// they start orbiting on the same pointerdown.

let down = null;
let hoverQueued = null;

canvas.addEventListener('pointerdown', (e) => {
  down = { x: e.clientX, y: e.clientY, t: e.timeStamp, button: e.button };
  if (sizing) {
    // The click ends the sizing; it starts neither a stroke nor an orbit.
    e.stopImmediatePropagation();
    finishSizing(e.button !== 0);
    down = null;
    return;
  }
  if (!viewer || !app.frame || app.stroke) return;
  if (app.state?.workspace !== 'sculpt' || e.button !== 0) return;
  const hit = viewer.pick(e.clientX, e.clientY);
  if (!hit) return; // empty space: orbit (with Shift or Ctrl: pan)
  viewer.controls.enabled = false;
  try {
    canvas.setPointerCapture(e.pointerId);
  } catch {
    // A pointer the browser does not track (a synthetic one) is not captured.
  }
  // Shift-drag smooths whatever brush is chosen.
  if (e.shiftKey) beginStroke(hit, e, 'smooth');
  else if (app.tool === 'mask') beginMaskStroke(hit, e);
  else beginStroke(hit, e);
});

canvas.addEventListener('pointermove', (e) => {
  lastPointer = [e.clientX, e.clientY];
  if (sizing) {
    updateSizing(e.clientX, e.clientY);
    return;
  }
  if (app.stroke && e.pointerId === app.stroke.pointerId && !app.stroke.ending) {
    strokeMove(e);
    return;
  }
  if (app.state?.workspace !== 'sculpt' || !viewer || e.buttons) return;
  // Brush cursor: at most one pick per displayed frame.
  const first = !hoverQueued;
  hoverQueued = { x: e.clientX, y: e.clientY };
  if (first) {
    requestAnimationFrame(() => {
      const q = hoverQueued;
      hoverQueued = null;
      if (app.stroke || sizing || app.state?.workspace !== 'sculpt') return;
      const hit = viewer.pick(q.x, q.y);
      if (hit) viewer.showBrush(hit.point, hit.normal, brushRadius());
      else viewer.hideBrush();
    });
  }
});

const pointerEnd = (e) => {
  if (app.stroke && e.pointerId === app.stroke.pointerId) {
    strokeUp();
    return;
  }
  if (e.type !== 'pointerup' || !down) return;
  const click = e.button === 0 && Math.hypot(e.clientX - down.x, e.clientY - down.y) < 5 && e.timeStamp - down.t < 600;
  down = null;
  if (click && app.state?.workspace === 'model') modelClick(e);
};
canvas.addEventListener('pointerup', pointerEnd);
canvas.addEventListener('pointercancel', pointerEnd);
canvas.addEventListener('lostpointercapture', pointerEnd);
canvas.addEventListener('pointerleave', () => {
  if (!app.stroke && !sizing) viewer?.hideBrush();
});
canvas.addEventListener('contextmenu', (e) => e.preventDefault());
viewer?.attachControls();

// ---- measurements for the end-to-end tests -----------------------------------

/** Orbit the camera a full turn in `n` animation frames; returns frames per
 * second. `proxy: true` draws as during a real orbit (motion state: lower
 * resolution, the navigation proxy above PROXY_ABOVE triangles); false draws
 * the full mesh at full resolution every frame. */
function benchOrbit(n = 120, { proxy = true } = {}) {
  if (proxy) viewer.beginMotion('bench');
  return new Promise((resolve) => {
    const c = viewer.controls;
    const target = c.target.clone();
    const offset = viewer.camera.position.clone().sub(target);
    const r = Math.hypot(offset.x, offset.z), y = offset.y;
    let i = 0, start = 0;
    const renderMs = [];
    const step = (now) => {
      if (i === 0) start = now;
      const a = Math.atan2(offset.x, offset.z) + (2 * Math.PI * i) / n;
      viewer.camera.position.set(target.x + r * Math.sin(a), target.y + y, target.z + r * Math.cos(a));
      viewer.camera.lookAt(target);
      const t0 = performance.now();
      viewer.renderNow();
      waitForGpu(); // so renderMs is real drawing time
      renderMs.push(performance.now() - t0);
      if (++i <= n) requestAnimationFrame(step);
      else {
        viewer.quietChange = true;
        c.update();
        viewer.quietChange = false;
        renderMs.sort((a2, b2) => a2 - b2);
        const out = {
          fps: (n * 1000) / (now - start), frames: n, medianRenderMs: renderMs[renderMs.length >> 1],
          proxyShown: !!viewer.proxyShown, proxyTriangles: viewer.proxyShown ? viewer.proxyTriangles : null,
          pixelRatio: viewer.renderer.getPixelRatio(),
        };
        if (proxy) viewer.endMotion('bench');
        resolve(out);
      }
    };
    requestAnimationFrame(step);
  });
}
/** Block until the GPU has drawn everything submitted. Chromium answers
 * gl.finish() without waiting for a software rasterizer; reading a pixel
 * back has to wait for the picture. Measurements only. */
const pixel = new Uint8Array(4);
function waitForGpu() {
  const gl = viewer.renderer.getContext();
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
}

/** The picture on screen (drawn with partial redraws during a stroke)
 * against a full redraw of the same state: how many pixels differ, and by
 * how much at most (0..255 per channel). */
function comparePartialToFull() {
  const gl = viewer.renderer.getContext();
  if (viewer.pendingRender) viewer.renderNow(); // the pending (partial) picture
  const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
  const a = new Uint8Array(4 * w * h), b = new Uint8Array(4 * w * h);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, a);
  viewer.damage = 'full';
  viewer.renderNow();
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, b);
  let differ = 0, maxDiff = 0;
  for (let i = 0; i < a.length; i += 4) {
    const d = Math.max(Math.abs(a[i] - b[i]), Math.abs(a[i + 1] - b[i + 1]), Math.abs(a[i + 2] - b[i + 2]));
    if (d > 0) differ++;
    if (d > maxDiff) maxDiff = d;
  }
  return { width: w, height: h, pixels: w * h, differ, maxDiff, partialRenders: viewer.partialRenders };
}

/** Median time of `n` full pictures at rest (the GPU waited for each). */
function benchRender(n = 5) {
  const ms = [];
  viewer.renderNow();
  waitForGpu();
  for (let i = 0; i < n; i++) {
    const t0 = performance.now();
    viewer.renderNow();
    waitForGpu();
    ms.push(performance.now() - t0);
  }
  ms.sort((a, b) => a - b);
  return { medianMs: ms[n >> 1], pixelRatio: viewer.renderer.getPixelRatio(), proxyShown: !!viewer.proxyShown, motion: [...viewer.motion] };
}

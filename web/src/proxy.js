// Mesh helpers on plain typed arrays: the vertex → triangle adjacency used
// for local normal updates, and the navigation proxy (vertex clustering) that
// stands in for a huge mesh while the camera moves.

/** Vertex → triangle adjacency in CSR form: the triangles around vertex v
 * are tri[start[v] .. start[v+1]). */
export function vertexTriangles(nv, tris) {
  const nt = tris.length / 3;
  const start = new Uint32Array(nv + 1);
  for (let i = 0; i < tris.length; i++) start[tris[i] + 1]++;
  for (let v = 0; v < nv; v++) start[v + 1] += start[v];
  const fill = start.slice(0, nv);
  const tri = new Uint32Array(tris.length);
  for (let t = 0; t < nt; t++) {
    tri[fill[tris[3 * t]]++] = t;
    tri[fill[tris[3 * t + 1]]++] = t;
    tri[fill[tris[3 * t + 2]]++] = t;
  }
  return { start, tri };
}

/** Sorted indices → [start, count] runs, joining runs closer than `gap`.
 * Returns null when more than `maxRuns` runs would be needed. */
export function indexRuns(sorted, n, gap = 32, maxRuns = 48) {
  const runs = [];
  if (!n) return runs;
  let a = sorted[0], b = a;
  for (let i = 1; i < n; i++) {
    const v = sorted[i];
    if (v <= b + gap) b = v;
    else {
      runs.push(a, b - a + 1);
      if (runs.length > 2 * maxRuns) return null;
      a = b = v;
    }
  }
  runs.push(a, b - a + 1);
  return runs.length > 2 * maxRuns ? null : runs;
}

// Open-addressing hash of u32 keys → dense ids (keys are stored + 1, 0 = empty).
function makeTable(n) {
  let size = 1;
  while (size < 2 * n) size <<= 1;
  return { keys: new Uint32Array(size), ids: new Uint32Array(size), mask: size - 1, count: 0 };
}
function lookup(tab, key) {
  const k1 = key + 1;
  let h = Math.imul(key, 0x9e3779b1) >>> 0;
  for (;;) {
    const s = h & tab.mask;
    const k = tab.keys[s];
    if (k === k1) return tab.ids[s];
    if (k === 0) {
      tab.keys[s] = k1;
      tab.ids[s] = tab.count;
      return tab.count++;
    }
    h = s + 1;
  }
}

function gridCells(p, nv, lo, cell, g, tab, out) {
  const [x0, y0, z0] = lo;
  const inv = 1 / cell, gm = g - 1;
  for (let v = 0; v < nv; v++) {
    const ix = Math.min(gm, Math.max(0, ((p[3 * v] - x0) * inv) | 0));
    const iy = Math.min(gm, Math.max(0, ((p[3 * v + 1] - y0) * inv) | 0));
    const iz = Math.min(gm, Math.max(0, ((p[3 * v + 2] - z0) * inv) | 0));
    const id = lookup(tab, ix + g * (iy + g * iz));
    if (out) out[v] = id;
  }
  return tab.count;
}

/**
 * Decimate by vertex clustering on a uniform grid: every vertex goes to its
 * cell, a cell becomes one vertex (the mean of its members), triangles whose
 * corners land in three different cells survive (duplicates dropped).
 * The grid is sized from a first count so that about `targetTris` remain
 * (a closed surface has about twice as many triangles as vertices).
 * Returns { positions, normals, index, nv, nt } with area-weighted normals.
 */
/** Area-weighted vertex normals of triangles `index` over `pos`, written
 * into `out` (zero-filled here), unit length. */
export function areaNormals(pos, index, out) {
  out.fill(0);
  for (let i = 0; i < index.length; i += 3) {
    const a = 3 * index[i], b = 3 * index[i + 1], c = 3 * index[i + 2];
    const ux = pos[b] - pos[a], uy = pos[b + 1] - pos[a + 1], uz = pos[b + 2] - pos[a + 2];
    const vx = pos[c] - pos[a], vy = pos[c + 1] - pos[a + 1], vz = pos[c + 2] - pos[a + 2];
    const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    out[a] += nx; out[a + 1] += ny; out[a + 2] += nz;
    out[b] += nx; out[b + 1] += ny; out[b + 2] += nz;
    out[c] += nx; out[c + 1] += ny; out[c + 2] += nz;
  }
  for (let i = 0; i < out.length; i += 3) {
    const l = Math.hypot(out[i], out[i + 1], out[i + 2]) || 1;
    out[i] /= l; out[i + 1] /= l; out[i + 2] /= l;
  }
}

export function clusterDecimate(positions, tris, bbox, targetTris = 120000, mask = null) {
  const nv = positions.length / 3, nt = tris.length / 3;
  const ext = Math.max(bbox.max[0] - bbox.min[0], bbox.max[1] - bbox.min[1], bbox.max[2] - bbox.min[2]) || 1;
  const lo = [bbox.min[0] - 1e-6 * ext, bbox.min[1] - 1e-6 * ext, bbox.min[2] - 1e-6 * ext];
  const targetV = targetTris / 2;
  // Occupied cells of a surface grow with the square of the resolution.
  let g = 128;
  let occupied = gridCells(positions, nv, lo, (ext * 1.000002) / g, g, makeTable(nv), null);
  g = Math.max(8, Math.min(1600, Math.floor(g * Math.sqrt(targetV / Math.max(1, occupied)))));
  const cell = (ext * 1.000002) / g;
  const vid = new Uint32Array(nv);
  const m = gridCells(positions, nv, lo, cell, g, makeTable(nv), vid);

  const sum = new Float64Array(3 * m), cnt = new Uint32Array(m);
  for (let v = 0; v < nv; v++) {
    const c = vid[v];
    sum[3 * c] += positions[3 * v];
    sum[3 * c + 1] += positions[3 * v + 1];
    sum[3 * c + 2] += positions[3 * v + 2];
    cnt[c]++;
  }
  const pos = new Float32Array(3 * m);
  for (let c = 0; c < m; c++) {
    const w = 1 / (cnt[c] || 1);
    pos[3 * c] = sum[3 * c] * w;
    pos[3 * c + 1] = sum[3 * c + 1] * w;
    pos[3 * c + 2] = sum[3 * c + 2] * w;
  }

  // Surviving triangles, each cell triple once (keyed by its sorted triple).
  let index = new Uint32Array(Math.min(3 * nt, 3 * (4 * targetV + 1024)));
  let k = 0;
  let size = 1;
  while (size < 2 * (index.length / 3)) size <<= 1;
  const ha = new Int32Array(size).fill(-1), hb = new Uint32Array(size), hc = new Uint32Array(size);
  const hmask = size - 1;
  for (let t = 0; t < nt; t++) {
    const a = vid[tris[3 * t]], b = vid[tris[3 * t + 1]], c = vid[tris[3 * t + 2]];
    if (a === b || b === c || a === c) continue;
    let s0 = a, s1 = b, s2 = c, x;
    if (s0 > s1) { x = s0; s0 = s1; s1 = x; }
    if (s1 > s2) { x = s1; s1 = s2; s2 = x; }
    if (s0 > s1) { x = s0; s0 = s1; s1 = x; }
    let h = (Math.imul(s0, 0x9e3779b1) ^ Math.imul(s1, 0x85ebca6b) ^ Math.imul(s2, 0xc2b2ae35)) >>> 0;
    let dup = false;
    for (;;) {
      const slot = h & hmask;
      if (ha[slot] === -1) {
        ha[slot] = s0; hb[slot] = s1; hc[slot] = s2;
        break;
      }
      if (ha[slot] === s0 && hb[slot] === s1 && hc[slot] === s2) { dup = true; break; }
      h = slot + 1;
    }
    if (dup) continue;
    if (k + 3 > index.length) break; // grid estimate far off: keep what fits
    index[k++] = a; index[k++] = b; index[k++] = c;
  }
  index = index.slice(0, k);

  const nrm = new Float32Array(3 * m);
  areaNormals(pos, index, nrm);
  // The sculpt mask of a cluster: the share of its vertices masked.
  let masked = null;
  if (mask && mask.length === nv) {
    masked = new Float32Array(m);
    for (let v = 0; v < nv; v++) masked[vid[v]] += mask[v];
    for (let c = 0; c < m; c++) masked[c] /= cnt[c] || 1;
  }
  return { positions: pos, normals: nrm, index, nv: m, nt: k / 3, grid: g, masked };
}

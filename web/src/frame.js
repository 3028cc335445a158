// Binary mesh frames, exactly as laid out in PROTOCOL.md.
//
// The typed arrays returned are views into the received ArrayBuffer (no
// copies): a WebSocket with binaryType 'arraybuffer' hands us a fresh buffer
// starting at offset 0, and every section of the frame is 4-byte aligned.

export const FLAG_PREVIEW = 1;
export const FLAG_MASK = 2;
export const FLAG_POSITIONS_ONLY = 4;
export const FLAG_SPARSE = 8;
export const FLAG_SCULPT_MASK = 16;
export const FLAG_PATCH = 32;
const MAGIC = 0x48534d48; // 'HMSH' read as a little-endian u32

const pad4 = (n) => (n + 3) & ~3;

export class FrameError extends Error {}

/**
 * Parse one frame. `prev` is the last parsed full-or-positions frame; a
 * positions-only frame borrows its connectivity arrays (tris, triFace, edges).
 *
 * A sparse frame (bits 2 and 3) carries only the vertices that moved:
 * `sparseIdx` (u32 × k) and `sparsePos` (f32 × 3k). Its `positions` is the
 * previous frame's array, NOT yet updated: the caller applies the change
 * (the viewer does it in place, see applySparse) before using the frame.
 */
export function parseFrame(buf, prev) {
  if (buf.byteLength < 32) throw new FrameError(`mesh frame too short (${buf.byteLength} bytes)`);
  const dv = new DataView(buf);
  if (dv.getUint32(0, true) !== MAGIC) throw new FrameError('mesh frame: bad magic');
  const format = dv.getUint32(4, true);
  if (format !== 1) throw new FrameError(`mesh frame: unsupported format version ${format}`);
  const flags = dv.getUint32(8, true);
  const version = dv.getUint32(12, true);
  const nv = dv.getUint32(16, true);
  const nt = dv.getUint32(20, true);
  const ne = dv.getUint32(24, true);
  const nf = dv.getUint32(28, true);
  const positionsOnly = (flags & FLAG_POSITIONS_ONLY) !== 0;

  let off = 32;
  const take = (bytes) => {
    if (off + bytes > buf.byteLength) throw new FrameError('mesh frame truncated');
    const at = off;
    off += pad4(bytes);
    return at;
  };
  if (flags & FLAG_PATCH) return parsePatch(buf, dv, prev, take, { flags, version, nv, nt, ne, nf });
  const sparse = positionsOnly && (flags & FLAG_SPARSE) !== 0;
  let positions, sparseIdx = null, sparsePos = null;
  if (sparse) {
    if (!prev) throw new FrameError('sparse mesh frame before any full frame');
    if (prev.nv !== nv) throw new FrameError('sparse frame does not match the previous vertex count');
    const k = dv.getUint32(take(4), true);
    if (k > nv) throw new FrameError(`sparse frame moves ${k} of ${nv} vertices`);
    sparseIdx = new Uint32Array(buf, take(4 * k), k);
    sparsePos = new Float32Array(buf, take(12 * k), 3 * k);
    for (let i = 0; i < k; i++) if (sparseIdx[i] >= nv) throw new FrameError('sparse frame: vertex index out of range');
    positions = prev.positions;
  } else {
    positions = new Float32Array(buf, take(12 * nv), 3 * nv);
  }

  let tris, triFace, edges;
  if (positionsOnly) {
    if (!prev) throw new FrameError('positions-only mesh frame before any full frame');
    if (prev.nt !== nt || prev.ne !== ne) throw new FrameError('positions-only frame does not match the previous connectivity');
    ({ tris, triFace, edges } = prev);
  } else {
    tris = new Uint32Array(buf, take(12 * nt), 3 * nt);
    triFace = new Uint32Array(buf, take(4 * nt), nt);
    edges = new Uint32Array(buf, take(8 * ne), 2 * ne);
  }
  const mask = flags & FLAG_MASK ? new Uint8Array(buf, take(nv), nv) : null;
  // The sculpt mask (whole frames only): 1 = no brush moves the vertex.
  const sculptMask = flags & FLAG_SCULPT_MASK ? new Uint8Array(buf, take(nv), nv) : null;

  return {
    flags, version, nv, nt, ne, nf, positions, tris, triFace, edges, mask, sculptMask,
    preview: (flags & FLAG_PREVIEW) !== 0,
    positionsOnly, sparse, sparseIdx, sparsePos,
  };
}

/**
 * Whether a parsed frame is a commit frame (PROTOCOL.md): sparse, no
 * vertex moved, no vanish mask, not a preview. The mesh the page shows is
 * then the committed document at the frame's version.
 */
export function isCommit(f) {
  return f.sparse && f.sparseIdx.length === 0 && !f.mask && !f.preview;
}

/**
 * A connectivity patch (bit 5): the slots of the previous frame's arrays
 * that changed. Like a sparse frame it borrows the previous arrays, NOT yet
 * updated: `patch` holds the changes (applyPatch writes them).
 */
function parsePatch(buf, dv, prev, take, h) {
  if (!prev) throw new FrameError('patch frame before any full frame');
  const from = [dv.getUint32(take(4), true), dv.getUint32(take(4), true), dv.getUint32(take(4), true)];
  if (from[0] !== prev.nv || from[1] !== prev.nt || from[2] !== prev.ne) {
    throw new FrameError('patch frame does not apply to the mesh on screen');
  }
  const list = (count, limit, what) => {
    const k = dv.getUint32(take(4), true);
    if (k > count) throw new FrameError(`patch frame: ${k} ${what} of ${count}`);
    const idx = new Uint32Array(buf, take(4 * k), k);
    let fresh = 0;
    for (let i = 0; i < k; i++) {
      if (idx[i] >= count || (i && idx[i] <= idx[i - 1])) throw new FrameError(`patch frame: bad ${what} list`);
      if (idx[i] >= limit) fresh++;
    }
    // Every slot beyond the old count is new: all must be listed.
    if (count > limit && fresh !== count - limit) throw new FrameError(`patch frame: new ${what} missing`);
    return idx;
  };
  const vIdx = list(h.nv, prev.nv, 'vertices');
  const vPos = new Float32Array(buf, take(12 * vIdx.length), 3 * vIdx.length);
  const tIdx = list(h.nt, prev.nt, 'triangles');
  const m = tIdx.length;
  const tVerts = new Uint32Array(buf, take(12 * m), 3 * m);
  const tFace = new Uint32Array(buf, take(4 * m), m);
  for (let i = 0; i < 3 * m; i++) if (tVerts[i] >= h.nv) throw new FrameError('patch frame: vertex index out of range');
  const eIdx = list(h.ne, prev.ne, 'edges');
  const eVerts = new Uint32Array(buf, take(8 * eIdx.length), 2 * eIdx.length);
  for (let i = 0; i < eVerts.length; i++) if (eVerts[i] >= h.nv) throw new FrameError('patch frame: edge index out of range');
  const vMask = h.flags & FLAG_SCULPT_MASK ? new Uint8Array(buf, take(vIdx.length), vIdx.length) : null;
  return {
    ...h, positions: prev.positions, tris: prev.tris, triFace: prev.triFace, edges: prev.edges,
    mask: null, sculptMask: null, preview: (h.flags & FLAG_PREVIEW) !== 0,
    positionsOnly: false, sparse: false, sparseIdx: null, sparsePos: null,
    patch: { from, vIdx, vPos, tIdx, tVerts, tFace, eIdx, eVerts, vMask },
  };
}

/**
 * Write a patch frame's changes into arrays: `store` holds the arrays the
 * previous frame's views live in ({ positions, tris, triFace, edges }, each
 * possibly longer than its count). Arrays without room for the new counts
 * are replaced by larger ones (old content copied). Returns the store
 * (`grown` says whether any array is new) and sets the frame's views.
 */
export function applyPatch(f, store) {
  const p = f.patch;
  const out = {
    positions: grow(Float32Array, store.positions, f.nv, 3, p.from[0]),
    tris: grow(Uint32Array, store.tris, f.nt, 3, p.from[1]),
    triFace: grow(Uint32Array, store.triFace, f.nt, 1, p.from[1]),
    edges: grow(Uint32Array, store.edges, f.ne, 2, p.from[2]),
  };
  out.grown = out.positions !== store.positions || out.tris !== store.tris || out.triFace !== store.triFace || out.edges !== store.edges;
  applySparse(out.positions, p.vIdx, p.vPos);
  const { tIdx, tVerts, tFace, eIdx, eVerts } = p;
  for (let i = 0; i < tIdx.length; i++) {
    const t = tIdx[i];
    out.tris[3 * t] = tVerts[3 * i]; out.tris[3 * t + 1] = tVerts[3 * i + 1]; out.tris[3 * t + 2] = tVerts[3 * i + 2];
    out.triFace[t] = tFace[i];
  }
  for (let i = 0; i < eIdx.length; i++) {
    const e = eIdx[i];
    out.edges[2 * e] = eVerts[2 * i]; out.edges[2 * e + 1] = eVerts[2 * i + 1];
  }
  f.positions = out.positions.subarray(0, 3 * f.nv);
  f.tris = out.tris.subarray(0, 3 * f.nt);
  f.triFace = out.triFace.subarray(0, f.nt);
  f.edges = out.edges.subarray(0, 2 * f.ne);
  return out;
}

/** `old` (holding `had` items of `size`) when it has room for `n`, else a
 * larger array holding its first items. */
function grow(Type, old, n, size, had) {
  if (old.length >= size * n) return old;
  const out = new Type(size * (Math.ceil(1.25 * n) + 1024));
  out.set(old.subarray(0, size * Math.min(had, n)));
  return out;
}

/** Write a sparse frame's moved vertices into a full position array. */
export function applySparse(positions, idx, pos) {
  for (let i = 0, k = idx.length; i < k; i++) {
    const o = 3 * idx[i], s = 3 * i;
    positions[o] = pos[s];
    positions[o + 1] = pos[s + 1];
    positions[o + 2] = pos[s + 2];
  }
}

/** Build a frame (used by the mock server and unit checks). */
export function encodeFrame({ flags = 0, version, positions, tris, triFace, edges, nf, mask, sculptMask, sparse }) {
  // `sparse` (optional): the indices of the vertices that moved; the frame
  // then carries only those (flags get bits 2 and 3).
  const nv = positions.length / 3;
  if (sparse) flags |= FLAG_POSITIONS_ONLY | FLAG_SPARSE;
  const positionsOnly = (flags & FLAG_POSITIONS_ONLY) !== 0;
  const nt = tris.length / 3;
  const ne = edges.length / 2;
  if (mask) flags |= FLAG_MASK;
  if (sculptMask && !positionsOnly) flags |= FLAG_SCULPT_MASK;
  let size = 32 + (sparse ? 4 + 16 * sparse.length : 12 * nv);
  if (!positionsOnly) size += 12 * nt + 4 * nt + 8 * ne;
  if (mask) size += pad4(nv);
  if (flags & FLAG_SCULPT_MASK) size += pad4(nv);
  const buf = new ArrayBuffer(size);
  const dv = new DataView(buf);
  [MAGIC, 1, flags, version, nv, nt, ne, nf].forEach((v, i) => dv.setUint32(4 * i, v, true));
  let off = 32;
  if (sparse) {
    const k = sparse.length;
    dv.setUint32(off, k, true); off += 4;
    new Uint32Array(buf, off, k).set(sparse); off += 4 * k;
    const sp = new Float32Array(buf, off, 3 * k);
    for (let i = 0; i < k; i++) for (let c = 0; c < 3; c++) sp[3 * i + c] = positions[3 * sparse[i] + c];
    off += 12 * k;
  } else {
    new Float32Array(buf, off, 3 * nv).set(positions); off += 12 * nv;
  }
  if (!positionsOnly) {
    new Uint32Array(buf, off, 3 * nt).set(tris); off += 12 * nt;
    new Uint32Array(buf, off, nt).set(triFace); off += 4 * nt;
    new Uint32Array(buf, off, 2 * ne).set(edges); off += 8 * ne;
  }
  if (mask) {
    new Uint8Array(buf, off, nv).set(mask);
    off += pad4(nv);
  }
  if (flags & FLAG_SCULPT_MASK) new Uint8Array(buf, off, nv).set(sculptMask);
  return buf;
}

// SPDX-License-Identifier: MIT
// Generated meshes of the WebAssembly package's tests (wasm_test.mjs, wasm_threads_test.mjs).
// Seeded generator (mulberry32) for the meshes below.
export function random(seed) {
  return () => {
    seed = (seed + 0x6d2b79f5) | 0;
    let t = Math.imul(seed ^ (seed >>> 15), 1 | seed);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// A bumpy UV sphere with a seam, one mirrored half (u flipped beyond the equator's half),
// and slivers: triangles collapsed to a line, to a point, and with all corners at one UV.
export function generated(segments, seed) {
  const rand = random(seed);
  const position = [], normal = [], texcoord = [];
  for (let j = 0; j <= segments; ++j) {
    for (let i = 0; i <= segments; ++i) {
      const u = i / segments, v = j / segments, phi = 2 * Math.PI * u, theta = Math.PI * v;
      const r = 1 + 0.05 * rand();
      const p = [r * Math.sin(theta) * Math.cos(phi), r * Math.cos(theta), -r * Math.sin(theta) * Math.sin(phi)];
      position.push(...p);
      const l = Math.hypot(...p);
      normal.push(p[0] / l, p[1] / l, p[2] / l);
      texcoord.push(u < 0.5 ? u : 1 - u, v);  // mirrored half
    }
  }
  const indices = [];
  for (let j = 0; j < segments; ++j) {
    for (let i = 0; i < segments; ++i) {
      const a = j * (segments + 1) + i, b = a + 1, c = a + segments + 1, d = c + 1;
      indices.push(a, d, b, a, c, d);
    }
  }
  // Slivers: a line (two corners at one vertex), a zero-UV triangle, a point.
  const n = indices.length / 3;
  for (let k = 0; k < 6; ++k) {
    const t = Math.floor(rand() * n);
    const kind = k % 3;
    if (kind === 0) indices[3 * t + 2] = indices[3 * t + 1];
    if (kind === 1) {
      const v = indices[3 * t];
      for (const w of [indices[3 * t + 1], indices[3 * t + 2]]) texcoord.splice(2 * w, 2, texcoord[2 * v], texcoord[2 * v + 1]);
    }
    if (kind === 2) indices[3 * t + 1] = indices[3 * t + 2] = indices[3 * t];
  }
  return {
    position: new Float32Array(position), normal: new Float32Array(normal), texcoord: new Float32Array(texcoord),
    indices: new Uint32Array(indices),
  };
}

export function deindex(mesh) {
  const n = mesh.indices.length;
  const out = { position: new Float32Array(3 * n), normal: new Float32Array(3 * n), texcoord: new Float32Array(2 * n) };
  mesh.indices.forEach((v, c) => {
    out.position.set(mesh.position.subarray(3 * v, 3 * v + 3), 3 * c);
    out.normal.set(mesh.normal.subarray(3 * v, 3 * v + 3), 3 * c);
    out.texcoord.set(mesh.texcoord.subarray(2 * v, 2 * v + 2), 2 * c);
  });
  return out;
}

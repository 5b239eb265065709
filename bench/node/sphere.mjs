// SPDX-License-Identifier: MIT
// The UV sphere the library is measured on (tools/bench/analytic_surfaces.cpp, "sphere"):
// about `target` triangles, normal = position. indexedSphere: its shared vertices and indices
// (what the native kernel bench's sphere-1eN is); sphere: the same de-indexed, every 3 vertices
// one triangle.
export function indexedSphere(target) {
  const n = Math.max(2, Math.round(Math.sqrt(target / 2)));
  const position = new Float32Array(3 * (n + 1) * (n + 1)), texcoord = new Float32Array(2 * (n + 1) * (n + 1));
  for (let j = 0, v = 0; j <= n; ++j) {
    for (let i = 0; i <= n; ++i, ++v) {
      const u = i / n, w = j / n, phi = 2 * Math.PI * u, theta = Math.PI * w;
      const st = (j === 0 || j === n) ? 0 : Math.sin(theta), ct = j === 0 ? 1 : j === n ? -1 : Math.cos(theta);
      position.set([st * Math.cos(phi), ct, -st * Math.sin(phi)], 3 * v);
      texcoord.set([u, w], 2 * v);
    }
  }
  const indices = new Uint32Array(6 * n * n);
  for (let j = 0, k = 0; j < n; ++j) {
    for (let i = 0; i < n; ++i, k += 6) {
      const a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      indices.set([a, d, b, a, c, d], k);  // outward winding for this parameterization
    }
  }
  return { position, normal: position, texcoord, indices };
}

export function sphere(target) {
  const { position: vertexPosition, texcoord: vertexTexcoord, indices } = indexedSphere(target);
  const corners = indices.length;
  const position = new Float32Array(corners * 3), normal = new Float32Array(corners * 3), texcoord = new Float32Array(corners * 2);
  indices.forEach((vi, c) => {
    position.set(vertexPosition.subarray(3 * vi, 3 * vi + 3), 3 * c);
    normal.set(vertexPosition.subarray(3 * vi, 3 * vi + 3), 3 * c);
    texcoord.set(vertexTexcoord.subarray(2 * vi, 2 * vi + 2), 2 * c);
  });
  return { position, normal, texcoord };
}

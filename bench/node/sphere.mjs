// SPDX-License-Identifier: MIT
// The UV sphere the library is measured on (tools/bench/analytic_surfaces.cpp, "sphere"),
// de-indexed: about `target` triangles, every 3 vertices one triangle, normal = position.
export function sphere(target) {
  const n = Math.max(2, Math.round(Math.sqrt(target / 2)));
  const vertices = [];
  for (let j = 0; j <= n; ++j) {
    for (let i = 0; i <= n; ++i) {
      const u = i / n, v = j / n, phi = 2 * Math.PI * u, theta = Math.PI * v;
      const st = (j === 0 || j === n) ? 0 : Math.sin(theta), ct = j === 0 ? 1 : j === n ? -1 : Math.cos(theta);
      const p = [st * Math.cos(phi), ct, -st * Math.sin(phi)];
      vertices.push({ p, uv: [u, v] });
    }
  }
  const indices = [];
  for (let j = 0; j < n; ++j) {
    for (let i = 0; i < n; ++i) {
      const a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      indices.push(a, d, b, a, c, d);  // outward winding for this parameterization
    }
  }
  const corners = indices.length;
  const position = new Float32Array(corners * 3), normal = new Float32Array(corners * 3), texcoord = new Float32Array(corners * 2);
  indices.forEach((vi, c) => {
    position.set(vertices[vi].p, 3 * c);
    normal.set(vertices[vi].p, 3 * c);
    texcoord.set(vertices[vi].uv, 2 * c);
  });
  return { position, normal, texcoord };
}

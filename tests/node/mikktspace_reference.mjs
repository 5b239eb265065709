// SPDX-License-Identifier: MIT
// Runs the reference MikkTSpace (npm `mikktspace`, WebAssembly) on de-indexed meshes.
// Usage: node mikktspace_reference.mjs IN OUT [IN OUT ...]
// IN:  uint32 corner count n, then n*3 float32 positions, n*3 normals, n*2 UVs (little endian).
// OUT: n*4 float32 tangents (xyz, w) exactly as the reference returns them (its own UV
//      convention: negate w for glTF).
import fs from 'node:fs';
import { generateTangents } from 'mikktspace';

const args = process.argv.slice(2);
if (args.length === 0 || args.length % 2 !== 0) {
  console.error('usage: node mikktspace_reference.mjs IN OUT [IN OUT ...]');
  process.exit(2);
}
for (let i = 0; i < args.length; i += 2) {
  const bytes = fs.readFileSync(args[i]);
  const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
  const n = new Uint32Array(buffer, 0, 1)[0];
  const positions = new Float32Array(buffer, 4, n * 3);
  const normals = new Float32Array(buffer, 4 + n * 12, n * 3);
  const uvs = new Float32Array(buffer, 4 + n * 24, n * 2);
  const tangents = generateTangents(positions, normals, uvs);
  fs.writeFileSync(args[i + 1], Buffer.from(tangents.buffer, tangents.byteOffset, tangents.byteLength));
}

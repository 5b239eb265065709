// SPDX-License-Identifier: MIT
// Tangents in files written elsewhere (the example page, tests/browser) against the C++ library.
// Usage: node baked_vs_library.mjs ARRAYS_TOOL WORK_DIR FILE.glb...
// For every normal-mapped triangle-list primitive with NORMAL: the corners, de-indexed, go to
// tangent-arrays-tool (MikkTSpace, glTF's w); each corner's stored TANGENT must have the bits the
// library gives. Every file must pass the Khronos validator with 0 errors and have at least one
// such primitive. Exits 1 on any failure.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import validator from 'gltf-validator';

const [tool, workDir, ...files] = process.argv.slice(2);
if (!tool || !workDir || files.length === 0) {
  console.error('usage: node baked_vs_library.mjs ARRAYS_TOOL WORK_DIR FILE.glb...');
  process.exit(2);
}
fs.rmSync(workDir, { recursive: true, force: true });
let failures = 0, runs = 0;
const io = new NodeIO().registerExtensions(ALL_EXTENSIONS);

// The attribute's value at each corner, as float32.
function corners(accessor, indices, count) {
  const width = accessor.getElementSize();
  const out = new Float32Array(width * count);
  const element = [];
  for (let c = 0; c < count; ++c) out.set(accessor.getElement(indices ? indices.getScalar(c) : c, element), width * c);
  return out;
}

function library(position, normal, texcoord) {
  const dir = path.join(workDir, `arrays-${runs++}`);
  fs.mkdirSync(dir, { recursive: true });
  const write = (name, array) => fs.writeFileSync(path.join(dir, name), Buffer.from(array.buffer, array.byteOffset, array.byteLength));
  write('positions.f32', position);
  write('normals.f32', normal);
  write('uvs.f32', texcoord);
  write('indices.u32', Uint32Array.from({ length: position.length / 3 }, (_, i) => i));
  execFileSync(tool, [dir, 'mikktspace', 'top-left']);
  const bytes = fs.readFileSync(path.join(dir, 'tangents.f32'));
  return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
}

for (const file of files) {
  const name = path.basename(file);
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), { uri: name });
  if (report.issues.numErrors > 0) {
    console.log(`FAIL ${name}: ${report.issues.numErrors} validator errors`);
    failures++;
  }
  const document = await io.read(file);
  let compared = 0;
  for (const mesh of document.getRoot().listMeshes()) {
    mesh.listPrimitives().forEach((primitive, p) => {
      const info = primitive.getMaterial()?.getNormalTextureInfo();
      if (!primitive.getMaterial()?.getNormalTexture() || primitive.getMode() !== 4) return;
      const position = primitive.getAttribute('POSITION'), normal = primitive.getAttribute('NORMAL');
      const texcoord = primitive.getAttribute(`TEXCOORD_${info.getTexCoord()}`), tangent = primitive.getAttribute('TANGENT');
      if (!position || !normal || !texcoord) return;
      const label = `${name} mesh "${mesh.getName()}" primitive ${p}`;
      if (!tangent) {
        console.log(`FAIL ${label}: normal-mapped, but no TANGENT`);
        failures++;
        return;
      }
      const indices = primitive.getIndices();
      const count = indices ? indices.getCount() : position.getCount();
      const stored = corners(tangent, indices, count);
      const theirs = library(corners(position, indices, count), corners(normal, indices, count), corners(texcoord, indices, count));
      let same = 0;
      for (let i = 0; i < stored.length; ++i) same += Object.is(stored[i], theirs[i]);
      const ok = same === stored.length && stored.length === theirs.length;
      console.log(`${ok ? 'ok  ' : 'FAIL'} ${label}: ${count} corners, ${same} of ${stored.length} components bit-identical to the C++ library`);
      failures += !ok;
      compared++;
    });
  }
  if (compared === 0) {
    console.log(`FAIL ${name}: no normal-mapped primitive with tangents to compare`);
    failures++;
  }
}
console.log(failures === 0 ? 'all passed' : `${failures} failed`);
process.exit(failures === 0 ? 0 : 1);

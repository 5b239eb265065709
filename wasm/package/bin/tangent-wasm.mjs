#!/usr/bin/env node
// SPDX-License-Identifier: MIT
// tangent-wasm IN OUT [--force]: bakes MikkTSpace tangents into every normal-mapped
// triangle primitive of a glTF/GLB with glTF-Transform (its unweld, tangents and weld steps)
// and this package's generateTangents. Needs @gltf-transform/core, /extensions and /functions
// (peer dependencies). Never writes over IN; OUT appears whole or not at all.
import fs from 'node:fs';
import path from 'node:path';
import { generateTangents } from '../index.mjs';

function fail(message) {
  console.error(`tangent-wasm: ${message}`);
  process.exit(1);
}

const args = process.argv.slice(2);
// --force replaces an existing OUT. (--overwrite means "recompute valid tangents too" in
// `tangent bake` and glTF-Transform's tangents(); here every tangent is recomputed anyway.)
if (args.includes('--overwrite')) {
  console.error('tangent-wasm: --overwrite is not an option here; --force replaces an existing output');
  process.exit(2);
}
const usage = 'usage: tangent-wasm IN.gltf|IN.glb OUT.gltf|OUT.glb [--force]';
if (args.includes('--help') || args.includes('-h')) {
  console.log(`${usage}\n\nBakes MikkTSpace tangents into every normal-mapped triangle primitive with glTF-Transform\n` +
    'and this package\'s generateTangents. Never writes over IN; --force replaces an existing OUT.');
  process.exit(0);
}
const force = args.includes('--force');
const files = args.filter((a) => a !== '--force');
if (files.length !== 2) {
  console.error(`tangent-wasm: expected IN and OUT (${usage})`);
  process.exit(2);
}
const [input, output] = files.map((f) => path.resolve(f));
if (!fs.existsSync(input)) fail(`${input}: no such file`);
if (input === output) fail(`${output}: is the input; choose another output`);
if (fs.existsSync(output) && !force) fail(`${output}: exists (pass --force to replace it)`);

let gltf;
try {
  gltf = {
    core: await import('@gltf-transform/core'),
    extensions: await import('@gltf-transform/extensions'),
    functions: await import('@gltf-transform/functions'),
  };
} catch {
  fail('needs @gltf-transform/core, @gltf-transform/extensions and @gltf-transform/functions: npm install them beside this package');
}
const io = new gltf.core.NodeIO().registerExtensions(gltf.extensions.ALL_EXTENSIONS);
let document;
try {
  document = await io.read(input);
} catch (e) {
  fail(`${input}: cannot be read: ${e.message}`);
}
await document.transform(gltf.functions.unweld(), gltf.functions.tangents({ generateTangents, overwrite: true }),
  gltf.functions.weld());
if (output.endsWith('.glb')) {
  const temporary = path.join(path.dirname(output), `.${path.basename(output)}.tmp-${process.pid}`);
  fs.writeFileSync(temporary, await io.writeBinary(document));
  fs.renameSync(temporary, output);
} else {
  await io.write(output, document);
}
console.log(`tangent-wasm: wrote ${output}`);

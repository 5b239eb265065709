#!/usr/bin/env node
// SPDX-License-Identifier: MIT
// npm's prepack step: a package without its WebAssembly builds is never packed. Where dist/
// lacks a build and emscripten (em++) is on the PATH it runs wasm/build.sh; without emscripten
// it stops and says what to run.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const packageDir = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const builds = ['dist/tangent_wasm.cjs', 'dist/tangent_wasm.browser.mjs', 'dist/browser.mjs', 'dist/threads.mjs',
  'dist/tangent_wasm_threads.cjs', 'dist/tangent_wasm_threads.worker.js', 'dist/package.json', 'dist/threads.browser.mjs',
  'dist/tangent_wasm_threads.browser.mjs', 'dist/tangent_wasm_threads.browser.worker.js'];
const missing = () => builds.filter((file) => !fs.existsSync(path.join(packageDir, file)));

if (missing().length === 0) process.exit(0);
const hasEmscripten = spawnSync('em++', ['--version'], { stdio: 'ignore' }).status === 0;
const build = path.join(packageDir, '..', 'build.sh');
if (!fs.existsSync(build)) {
  console.error(`libtangent-wasm: ${missing().join(', ')} missing, and this folder is not the package's folder in a ` +
    'libtangent checkout (no ../build.sh): run wasm/build.sh in the checkout, then npm pack in wasm/package');
  process.exit(1);
}
if (!hasEmscripten) {
  console.error(`libtangent-wasm: ${missing().join(', ')} missing, and emscripten (em++) is not on the PATH: ` +
    'run wasm/build.sh from the repository root (it installs Debian\'s emscripten), then npm pack again');
  process.exit(1);
}
console.error('libtangent-wasm: dist/ is incomplete; building it with wasm/build.sh');
const done = spawnSync('bash', [build], { stdio: 'inherit' });
if (done.status !== 0 || missing().length > 0) {
  console.error(`libtangent-wasm: wasm/build.sh failed; ${missing().join(', ') || 'nothing'} missing`);
  process.exit(1);
}

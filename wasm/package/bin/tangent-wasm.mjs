#!/usr/bin/env node
// SPDX-License-Identifier: MIT
// tangent-wasm IN OUT [--force]: bakes MikkTSpace tangents into every normal-mapped
// triangle primitive of a glTF/GLB with glTF-Transform (its unweld, tangents and weld steps)
// and this package's generateTangents. Needs @gltf-transform/core, /extensions and /functions
// (peer dependencies).
// What it writes, it writes as `tangent bake` does (docs/security.md): never over IN or a file
// IN reads; OUT and each file beside a .gltf appear whole or not at all (a temporary file
// beside each, renamed into place; the .gltf last); only regular files are replaced, through a
// symbolic link only where the link leads to a name of the same extension; IN is read only
// inside its own folder.
import fs from 'node:fs';
import path from 'node:path';
import { generateTangents } from '../index.mjs';

function fail(message, status = 1) {
  console.error(`tangent-wasm: ${message}`);
  process.exit(status);
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
    'and this package\'s generateTangents. Never writes over IN or the files it reads; --force replaces an\n' +
    'existing OUT (and, for a .gltf, the files beside it that it writes).');
  process.exit(0);
}
const force = args.includes('--force');
const files = args.filter((a) => a !== '--force');
if (files.length !== 2) fail(`expected IN and OUT (${usage})`, 2);
const [input, output] = files.map((f) => path.resolve(f));
const extensionOf = (file) => path.extname(file).toLowerCase();
if (extensionOf(output) !== '.glb' && extensionOf(output) !== '.gltf') fail(`${output}: does not end in .glb or .gltf (${usage})`, 2);

// What a file that is not a regular one is, in words.
function kindOf(stat) {
  if (stat.isDirectory()) return 'a folder';
  if (stat.isFIFO()) return 'a FIFO';
  if (stat.isCharacterDevice()) return 'a character device';
  if (stat.isBlockDevice()) return 'a block device';
  if (stat.isSocket()) return 'a socket';
  return 'not a regular file';
}
const reason = (error) => error.code === 'ENOENT' ? 'no such file' : error.message;
// The file a glTF URI names relative to `folder`, or null where it is not a relative path that
// stays inside the folder (a scheme, an absolute path, `..` out of it). Throws URIError on a
// malformed percent-encoding.
function fileInFolder(folder, uri) {
  const relative = decodeURIComponent(uri);
  const file = path.resolve(folder, relative);
  const inside = path.relative(folder, file);
  if (/^[a-z][a-z0-9+.-]*:/i.test(uri) || path.isAbsolute(relative) || inside.startsWith('..') || path.isAbsolute(inside)) return null;
  return file;
}
const identity = (stat) => `${stat.dev}:${stat.ino}`;

// The input and every file it names (buffers, images): regular files inside its folder. Their
// identities, so that no output lands on one of them (a hard link or a link included).
function inputJson(file, size) {
  const fd = fs.openSync(file, 'r');
  try {
    const read = (length, position) => {
      const bytes = Buffer.alloc(length);
      let done = 0;
      while (done < length) {
        const n = fs.readSync(fd, bytes, done, length - done, position + done);
        if (n === 0) break;
        done += n;
      }
      return bytes.subarray(0, done);
    };
    const header = read(20, 0);
    if (header.length === 20 && header.readUInt32LE(0) === 0x46546c67) {  // 'glTF': its JSON chunk only
      const length = header.readUInt32LE(12);
      if (header.readUInt32LE(16) !== 0x4e4f534a || 20 + length > size) throw new Error('a .glb without its JSON chunk');
      return JSON.parse(read(length, 20).toString('utf8'));
    }
    return JSON.parse(read(size, 0).toString('utf8'));
  } finally {
    fs.closeSync(fd);
  }
}
const inputs = new Set();
{
  let stat;
  try {
    stat = fs.statSync(input);
  } catch (e) {
    fail(`${input}: ${reason(e)}`);
  }
  if (!stat.isFile()) fail(`${input}: is ${kindOf(stat)}, not a glTF file`);
  inputs.add(identity(stat));
  let json;
  try {
    json = inputJson(input, stat.size);
  } catch (e) {
    fail(`${input}: cannot be read: ${e.message}`);
  }
  const folder = path.dirname(input);
  for (const [list, name] of [[json.buffers, 'buffers'], [json.images, 'images']]) {
    (Array.isArray(list) ? list : []).forEach((item, i) => {
      const uri = item && typeof item.uri === 'string' ? item.uri : undefined;
      if (uri === undefined || uri.startsWith('data:')) return;
      let file;
      try {
        file = fileInFolder(folder, uri);
      } catch {
        fail(`${input}: ${name}[${i}].uri "${uri}" is not a valid URI`);
      }
      if (file === null) fail(`${input}: ${name}[${i}].uri "${uri}" is not a file in the asset's folder; not read`);
      let stat;
      try {
        stat = fs.statSync(file);
      } catch (e) {
        fail(`${input}: ${name}[${i}].uri "${uri}": ${file}: ${reason(e)}`);
      }
      if (!stat.isFile()) fail(`${input}: ${name}[${i}].uri "${uri}": ${file} is ${kindOf(stat)}; not read`);
      inputs.add(identity(stat));
    });
  }
}

// Where `file` (a name to write) leads: the file itself, or through symbolic links the name at
// their end, which must end in the extension `file` does (`out.glb` -> /etc/passwd would
// otherwise replace the system's file). A folder, device, FIFO or socket there is refused.
function targetOf(file) {
  let at = file;
  for (let links = 0; ; ++links) {
    if (links > 40) fail(`${file}: more than 40 symbolic links to follow (a loop?); not written`);
    let stat;
    try {
      stat = fs.lstatSync(at);
    } catch (e) {
      if (e.code !== 'ENOENT') fail(`${file}: cannot be examined: ${e.message}`);
      stat = null;
    }
    if (stat && stat.isSymbolicLink()) {
      try {
        at = path.resolve(path.dirname(at), fs.readlinkSync(at));
      } catch (e) {
        fail(`${file}: cannot read the link ${at}: ${e.message}`);
      }
      continue;
    }
    if (links > 0 && extensionOf(at) !== extensionOf(file)) {
      fail(`${file}: is a symbolic link to ${at}, which does not end in ${extensionOf(file) || 'an extension'} as the name ` +
        'given does; not written (a link is followed only to a file of the same kind: remove the link or choose another name)');
    }
    if (stat && !stat.isFile()) fail(`${file}: is ${kindOf(stat)}; not replaced (only a regular file is)`);
    return { file: at, stat };
  }
}

// The planned files: { name (as given), file (where it lands), bytes }; each checked before
// anything is written.
function plan(name, bytes) {
  const { file, stat } = targetOf(name);
  if (stat) {
    if (inputs.has(identity(stat))) fail(`${name}: is ${name === output ? 'the input' : 'a file the input reads'} (${file}); choose another output`);
    if (!force) fail(`${name}: exists (pass --force to replace it)`);
  }
  return { name, file, bytes };
}
// Checked before the bake too, so that a refusal comes before the work.
const outputTarget = plan(output, null);

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
  await document.transform(gltf.functions.unweld(), gltf.functions.tangents({ generateTangents, overwrite: true }),
    gltf.functions.weld());
} catch (e) {
  fail(`${input}: cannot be baked: ${e.message}`);
}

const planned = [];
try {
  if (extensionOf(output) === '.glb') {
    planned.push(plan(output, await io.writeBinary(document)));
  } else {
    // The buffers named after the output (glTF-Transform would keep the input's names, and
    // beside the input that is the input's own .bin); the images as the input names them.
    for (const buffer of document.getRoot().listBuffers()) buffer.setURI('');
    const folder = path.dirname(outputTarget.file);
    const basename = path.basename(outputTarget.file, path.extname(outputTarget.file));
    const { json, resources } = await io.writeJSON(document, { format: gltf.core.Format.GLTF, basename });
    for (const [uri, bytes] of Object.entries(resources)) {
      const file = fileInFolder(folder, uri);
      if (file === null) fail(`${output}: would write "${uri}" outside its folder; not written`);
      // An image the input has there already, byte for byte (an output beside its input): kept.
      const { stat } = targetOf(file);
      if (stat && stat.size === bytes.byteLength && Buffer.from(bytes).equals(fs.readFileSync(file))) continue;
      planned.push(plan(file, bytes));
    }
    planned.push(plan(output, Buffer.from(JSON.stringify(json, null, 2))));
  }
} catch (e) {
  fail(`${output}: cannot be written: ${e.message}`);
}

// Each file to a temporary beside it (created anew, flushed), then all renamed into place,
// the .gltf or .glb last; on a failure or a signal, no temporary is left.
const temporaries = [];
for (const signal of ['SIGINT', 'SIGTERM', 'SIGHUP']) {
  process.on(signal, () => {
    for (const temporary of temporaries) fs.rmSync(temporary, { force: true });
    process.exit(128 + (signal === 'SIGINT' ? 2 : signal === 'SIGTERM' ? 15 : 1));
  });
}
try {
  for (const item of planned) {
    if (item.file !== outputTarget.file) fs.mkdirSync(path.dirname(item.file), { recursive: true });  // an image's subfolder
    const temporary = path.join(path.dirname(item.file), `.${path.basename(item.file)}.tmp-${process.pid}`);
    const fd = fs.openSync(temporary, 'wx');
    temporaries.push(temporary);
    try {
      for (let done = 0; done < item.bytes.byteLength;) done += fs.writeSync(fd, item.bytes, done);
      fs.fsyncSync(fd);
    } finally {
      fs.closeSync(fd);
    }
    item.temporary = temporary;
  }
} catch (e) {
  for (const temporary of temporaries) fs.rmSync(temporary, { force: true });
  fail(`${output}: not written: ${e.message}`);
}
for (const item of planned) {
  try {
    fs.renameSync(item.temporary, item.file);
  } catch (e) {
    for (const other of planned) if (other.temporary) fs.rmSync(other.temporary, { force: true });
    fail(`${item.name}: cannot be renamed into place: ${e.message}`);
  }
  item.temporary = undefined;
}
console.log(`tangent-wasm: wrote ${output}`);

// SPDX-License-Identifier: MIT
// The example page's script (bundled into dist/main.js by `npm run build`): reads a dropped or
// chosen glTF (or ?url=FILE), computes MikkTSpace tangents for every normal-mapped primitive
// with libtangent-wasm through glTF-Transform's tangents(), lists the primitives and offers the
// result as a .glb. document.body.dataset.state is "waiting" once the page takes files, "busy"
// while it works on one, then "ready" (or "error: FILE: MESSAGE"), so that scripts and tests can
// wait for it. Files compressed with EXT_meshopt_compression (gltfpack -c) are read through
// meshoptimizer's decoder and written uncompressed.
import { WebIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { tangents, unweld, weld } from '@gltf-transform/functions';
import { generateTangents } from 'libtangent-wasm';
import { MeshoptDecoder } from 'meshoptimizer/decoder';

await MeshoptDecoder.ready;
const io = new WebIO().registerExtensions(ALL_EXTENSIONS).registerDependencies({ 'meshopt.decoder': MeshoptDecoder });
const status = document.getElementById('status');
const download = document.getElementById('download');
const table = document.getElementById('primitives');

// Errors name the file they come from.
async function named(name, read) {
  try {
    return await read();
  } catch (e) {
    throw new Error(`${name}: ${e.message}`);
  }
}

// A .glb alone, or a .gltf with the files its URIs name (matched by file name).
async function readDropped(files) {
  const glb = files.find((f) => /\.glb$/i.test(f.name));
  if (glb) return { name: glb.name, document: await named(glb.name, async () => io.readBinary(new Uint8Array(await glb.arrayBuffer()))) };
  const gltf = files.find((f) => /\.gltf$/i.test(f.name));
  if (!gltf) throw new Error(`no .glb or .gltf among ${files.map((f) => f.name).join(', ')}`);
  let json;
  try {
    json = JSON.parse(await gltf.text());
  } catch (e) {
    throw new Error(`${gltf.name}: not JSON: ${e.message}`);
  }
  const resources = {};
  for (const { uri } of [...(json.buffers ?? []), ...(json.images ?? [])]) {
    if (!uri || uri.startsWith('data:')) continue;
    const wanted = decodeURIComponent(uri).split('/').pop();
    const file = files.find((f) => f.name === wanted);
    if (!file) throw new Error(`${gltf.name} needs ${uri}: drop it together with the .gltf`);
    resources[uri] = new Uint8Array(await file.arrayBuffer());
  }
  return { name: gltf.name, document: await named(gltf.name, () => io.readJSON({ json, resources })) };
}

function listPrimitives(document) {
  const body = table.tBodies[0];
  body.replaceChildren();
  let baked = 0;
  for (const mesh of document.getRoot().listMeshes()) {
    mesh.listPrimitives().forEach((primitive, p) => {
      const material = primitive.getMaterial();
      const normalMapped = Boolean(material?.getNormalTexture());
      const tangent = primitive.getAttribute('TANGENT');
      const indices = primitive.getIndices();
      const vertices = primitive.getAttribute('POSITION')?.getCount() ?? 0;
      const why = !normalMapped ? 'not normal-mapped' : primitive.getMode() !== 4 ? 'not a triangle list: left alone'
        : !primitive.getAttribute('NORMAL') ? 'no NORMAL: left alone' : tangent ? 'computed' : 'none';
      baked += why === 'computed';
      const row = body.insertRow();
      for (const [text, numeric] of [[mesh.getName() || '(unnamed)'], [p, true], [vertices, true],
        [primitive.getMode() === 4 ? (indices ? indices.getCount() : vertices) / 3 : '–', true], [why]]) {
        const cell = row.insertCell();
        cell.textContent = String(text);
        if (numeric) cell.className = 'n';
      }
    });
  }
  table.hidden = false;
  return baked;
}

async function bake(name, document) {
  const started = performance.now();
  // glTF-Transform's tangents() takes unwelded triangles; weld() shares vertices again after.
  await document.transform(unweld(), tangents({ generateTangents, overwrite: true }), weld());
  // The page registers no meshopt encoder: the baked file is written without the compression.
  for (const extension of document.getRoot().listExtensionsUsed())
    if (extension.extensionName === 'EXT_meshopt_compression') extension.dispose();
  const glb = await io.writeBinary(document);
  const milliseconds = performance.now() - started;
  const baked = listPrimitives(document);
  URL.revokeObjectURL(download.href);
  download.href = URL.createObjectURL(new Blob([glb], { type: 'model/gltf-binary' }));
  download.download = name.replace(/\.(glb|gltf)$/i, '') + '.tangents.glb';
  download.hidden = false;
  status.className = '';
  status.textContent = `${name}: tangents computed for ${baked} primitive(s) in ${milliseconds.toFixed(0)} ms; ${glb.byteLength} bytes.`;
}

async function run(load) {
  document.body.dataset.state = 'busy';
  download.hidden = true;
  status.textContent = 'Working…';
  try {
    const { name, document: gltfDocument } = await load();
    await bake(name, gltfDocument);
    document.body.dataset.state = 'ready';
  } catch (e) {
    status.className = 'error';
    status.textContent = e.message;
    document.body.dataset.state = `error: ${e.message}`;
  }
}

const drop = document.getElementById('drop');
drop.addEventListener('dragover', (event) => {
  event.preventDefault();
  drop.classList.add('over');
});
drop.addEventListener('dragleave', () => drop.classList.remove('over'));
drop.addEventListener('drop', (event) => {
  event.preventDefault();
  drop.classList.remove('over');
  run(() => readDropped([...event.dataTransfer.files]));
});
document.getElementById('files').addEventListener('change', (event) => run(() => readDropped([...event.target.files])));

document.body.dataset.state = 'waiting';  // for a file: the handlers are in place
const url = new URLSearchParams(location.search).get('url');
if (url) {
  const name = decodeURIComponent(new URL(url, location.href).pathname.split('/').pop());
  run(async () => ({ name, document: await named(url, () => io.read(url)) }));
}

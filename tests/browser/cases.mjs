// SPDX-License-Identifier: MIT
// The computation of the package test's pages and workers: for each case in cases.json (arrays
// written by package_test.py), the package's tangents per corner, as base64 of float32 xyzw.
// `api` is the imported package, however the caller found it.
async function floats(url, Type) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  return new Type(await response.arrayBuffer());
}

function base64(typedArray) {
  let text = '';
  const bytes = new Uint8Array(typedArray.buffer, typedArray.byteOffset, typedArray.byteLength);
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

// Per corner: the indexed call's tangent of each corner's output vertex (glTF's w), and the
// de-indexed call's (MikkTSpace's w). `list`: the JSON file naming the cases; `options`: every
// call's options.
export async function computeCases({ generateTangents, generateTangentsIndexed }, base, list = 'cases.json', options = {}) {
  const names = await (await fetch(`${base}${list}`)).json();
  const result = {};
  for (const name of names) {
    const dir = `${base}cases/${name}/`;
    const position = await floats(`${dir}positions.f32`, Float32Array);
    const normal = await floats(`${dir}normals.f32`, Float32Array);
    const texcoord = await floats(`${dir}uvs.f32`, Float32Array);
    const indices = await floats(`${dir}indices.u32`, Uint32Array);
    const ours = generateTangentsIndexed(position, normal, texcoord, indices, options);
    const indexed = new Float32Array(4 * indices.length);
    ours.indices.forEach((v, c) => indexed.set(ours.tangents.subarray(4 * v, 4 * v + 4), 4 * c));
    const flat = { position: new Float32Array(3 * indices.length), normal: new Float32Array(3 * indices.length),
      texcoord: new Float32Array(2 * indices.length) };
    indices.forEach((v, c) => {
      flat.position.set(position.subarray(3 * v, 3 * v + 3), 3 * c);
      flat.normal.set(normal.subarray(3 * v, 3 * v + 3), 3 * c);
      flat.texcoord.set(texcoord.subarray(2 * v, 2 * v + 2), 2 * c);
    });
    result[name] = { indexed: base64(indexed), deindexed: base64(generateTangents(flat.position, flat.normal, flat.texcoord, options)) };
  }
  return result;
}

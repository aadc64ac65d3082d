#!/usr/bin/env node
// Decode the Draco-compressed GLB shipped in the npm package @gsimone/suzanne
// (index.js exports it as a base64 data: URI) into a plain, uncompressed glTF
// (JSON with an embedded base64 buffer) holding only POSITION and indices.
// make_meshes.cpp then reads that file with nlohmann-json; it cannot decode
// Draco itself.
//
// Usage: node decode_draco_gltf.js SOURCES_DIR
//   reads  SOURCES_DIR/suzanne/package/index.js
//   uses   SOURCES_DIR/draco3d/package (npm draco3d, Apache-2.0)
//   writes SOURCES_DIR/suzanne/suzanne-decoded.gltf
// Output is deterministic (same bytes every run for the same inputs).
'use strict';
const fs = require('fs');
const path = require('path');

const dir = process.argv[2];
if (!dir) {
  console.error('usage: node decode_draco_gltf.js SOURCES_DIR');
  process.exit(2);
}
const draco3d = require(path.resolve(dir, 'draco3d', 'package', 'draco3d.js'));

function readGlbFromPackage() {
  const js = fs.readFileSync(path.join(dir, 'suzanne', 'package', 'index.js'), 'utf8');
  const m = js.match(/"data:[^;"]*;base64,([A-Za-z0-9+/=]+)"/);
  if (!m) throw new Error('no base64 data URI found in suzanne/package/index.js');
  return Buffer.from(m[1], 'base64');
}

function parseGlb(buf) {
  if (buf.toString('ascii', 0, 4) !== 'glTF') throw new Error('not a GLB');
  const total = buf.readUInt32LE(8);
  let off = 12, json = null, bin = null;
  while (off < total) {
    const len = buf.readUInt32LE(off), type = buf.readUInt32LE(off + 4);
    const chunk = buf.subarray(off + 8, off + 8 + len);
    if (type === 0x4E4F534A) json = JSON.parse(chunk.toString('utf8'));
    else if (type === 0x004E4942) bin = chunk;
    off += 8 + len;
  }
  return { json, bin };
}

draco3d.createDecoderModule({}).then((D) => {
  const { json, bin } = parseGlb(readGlbFromPackage());
  const meshIndex = json.meshes.findIndex((m) => m.name === 'Suzanne');
  if (meshIndex < 0) throw new Error('mesh "Suzanne" not found');
  const prim = json.meshes[meshIndex].primitives[0];
  const ext = prim.extensions && prim.extensions.KHR_draco_mesh_compression;
  if (!ext) throw new Error('primitive is not Draco compressed (unexpected)');
  const bv = json.bufferViews[ext.bufferView];
  const data = bin.subarray(bv.byteOffset || 0, (bv.byteOffset || 0) + bv.byteLength);

  const decoder = new D.Decoder();
  const dbuf = new D.DecoderBuffer();
  dbuf.Init(new Int8Array(data), data.byteLength);
  if (decoder.GetEncodedGeometryType(dbuf) !== D.TRIANGULAR_MESH) throw new Error('not a mesh');
  const mesh = new D.Mesh();
  const st = decoder.DecodeBufferToMesh(dbuf, mesh);
  if (!st.ok() || mesh.ptr === 0) throw new Error('Draco decode failed: ' + st.error_msg());

  const nf = mesh.num_faces(), np = mesh.num_points();
  const attr = decoder.GetAttributeByUniqueId(mesh, ext.attributes.POSITION);
  const fa = new D.DracoFloat32Array();
  decoder.GetAttributeFloatForAllPoints(mesh, attr, fa);
  const pos = new Float32Array(np * 3);
  for (let i = 0; i < np * 3; i++) pos[i] = fa.GetValue(i);
  const ia = new D.DracoInt32Array();
  const idx = new Uint32Array(nf * 3);
  for (let f = 0; f < nf; f++) {
    decoder.GetFaceFromMesh(mesh, f, ia);
    for (let k = 0; k < 3; k++) idx[f * 3 + k] = ia.GetValue(k);
  }
  D.destroy(ia); D.destroy(fa); D.destroy(mesh); D.destroy(dbuf); D.destroy(decoder);

  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < np; i++)
    for (let k = 0; k < 3; k++) {
      min[k] = Math.min(min[k], pos[i * 3 + k]);
      max[k] = Math.max(max[k], pos[i * 3 + k]);
    }
  const small = np <= 65535;
  const idxBytes = Buffer.from(small ? new Uint16Array(idx).buffer : idx.buffer);
  const idxPadded = Buffer.concat([idxBytes, Buffer.alloc((4 - (idxBytes.length % 4)) % 4)]);
  const posBytes = Buffer.from(pos.buffer);
  const all = Buffer.concat([idxPadded, posBytes]);

  const node = json.nodes.find((n) => n.mesh === meshIndex) || {};
  const outNode = { name: 'Suzanne', mesh: 0 };
  for (const k of ['matrix', 'translation', 'rotation', 'scale']) if (node[k]) outNode[k] = node[k];

  const out = {
    asset: { version: '2.0', generator: 'sdfbench decode_draco_gltf.js (draco3d ' +
      require(path.resolve(dir, 'draco3d', 'package', 'package.json')).version + ') from @gsimone/suzanne' },
    buffers: [{ byteLength: all.length, uri: 'data:application/octet-stream;base64,' + all.toString('base64') }],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: idxBytes.length, target: 34963 },
      { buffer: 0, byteOffset: idxPadded.length, byteLength: posBytes.length, target: 34962 },
    ],
    accessors: [
      { bufferView: 0, componentType: small ? 5123 : 5125, count: idx.length, type: 'SCALAR' },
      { bufferView: 1, componentType: 5126, count: np, type: 'VEC3', min, max },
    ],
    meshes: [{ name: 'Suzanne', primitives: [{ attributes: { POSITION: 1 }, indices: 0, mode: 4 }] }],
    nodes: [outNode],
    scenes: [{ nodes: [0] }],
    scene: 0,
  };
  const outPath = path.join(dir, 'suzanne', 'suzanne-decoded.gltf');
  fs.writeFileSync(outPath, JSON.stringify(out, null, 1) + '\n');
  console.error(`decoded Suzanne: ${np} points, ${nf} triangles -> ${outPath}`);
}).catch((e) => { console.error(e); process.exit(1); });

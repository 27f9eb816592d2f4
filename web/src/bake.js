// Reading a prtkit bake (.glb, docs/formats-bake.md) in the page: three.js's GLTFLoader parses
// the glTF (it keeps the custom `_PRT_<MODE>_T<k>` VEC4 attributes, lower-cased), this file
// checks the container and the mesh (the domain: every vertex, or every texel of a lightmap over
// the mesh's lightmap UVs, relit per pixel), and every transfer goes through the one reader
// (transfer.js). Every problem is an Error with one line naming the file; nothing here touches
// the scene. tests/web/golden_check.mjs checks the texels, the pick order and the framing
// against the library (relight::packShaderRows, io::transferPreference, render::meshFraming).
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

import { bakeFile, bakeFormat, bands as kBands, domains, layouts, maxLightmapSide, modes } from 'prt:constants';
import { packRows, preferenceOrder, readTransfer } from './transfer.js';
import { textureShape } from './texels.js';
import { checkProbeGridDocument, probeCount, readProbeBake } from './probe_bake.js';
import { meshParts } from './parts.js';
import { checkHaarTransfer, isHaarEntry, readHaarBake } from './haar_bake.js';
import { rowDomain, useLightmapUvs } from './row_domain.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

const kBandsMaxLibrary = kBands.maxLibrary;

// ---- The file checked as the library reads it (io::decodeBake) ---------------------------------
// Before GLTFLoader builds anything from a file, its GLB container, JSON and every accessor the
// bake uses are checked as src/io/glb.cpp, bake_file.cpp, bake_mesh.cpp, transfer_codecs.cpp and
// src/gltf/accessor.cpp check them, with the library's limits ('prt:constants' bakeFile), so the
// page draws no file prt refuses (NaN positions, indices outside their part, rows of the wrong
// component type, versions that cannot hold what the file holds, lightmap UVs outside [0, 1]²)
// and GLTFLoader never meets a broken accessor. tests/web/bake_verdicts runs one corpus of valid
// and malformed bakes through both readers and requires the same verdict.
const kComponentBytes = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 };
const kComponentName = { 5120: 'BYTE', 5121: 'UNSIGNED_BYTE', 5122: 'SHORT', 5123: 'UNSIGNED_SHORT', 5125: 'UNSIGNED_INT', 5126: 'FLOAT' };
const kTypeComponents = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT2: 4, MAT3: 9, MAT4: 16 };
const kVectorType = ['', 'SCALAR', 'VEC2', 'VEC3', 'VEC4'];
const kFloat = 5126, kUint = 5125, kUshort = 5123, kShort = 5122, kUbyte = 5121;

/** glb::split: { json (text), bin (Uint8Array or null), length (the header's) }. */
function splitGlb(buffer, name) {
  const size = buffer.byteLength, b = new DataView(buffer);
  if (size < 12 || b.getUint32(0, true) !== 0x46546c67) fail(name, 'is not a glTF binary (.glb) file (bad magic)');
  if (b.getUint32(4, true) !== 2) fail(name, `glTF binary container version ${b.getUint32(4, true)}, expected 2`);
  const length = b.getUint32(8, true);
  if (length > size) fail(name, `is truncated: the header says ${length} bytes, the file has ${size}`);
  if (length < 20) fail(name, 'is truncated: no JSON chunk');
  const jsonLength = b.getUint32(12, true);
  if (b.getUint32(16, true) !== 0x4e4f534a) fail(name, 'first chunk is not JSON');
  if (20 + jsonLength > length) fail(name, 'is truncated: the JSON chunk runs past the end of the file');
  let bin = null;
  const binAt = 20 + jsonLength;
  if (binAt < length) {
    if (binAt + 8 > length) fail(name, 'is truncated: incomplete binary chunk header');
    const binLength = b.getUint32(binAt, true);
    if (binAt + 8 + binLength > length) fail(name, 'is truncated: the binary chunk runs past the end');
    if (b.getUint32(binAt + 4, true) !== 0x004e4942) fail(name, 'second chunk is not BIN');
    bin = new Uint8Array(buffer, binAt + 8, binLength);
  }
  let json;
  try {
    json = new TextDecoder('utf-8', { fatal: true }).decode(new Uint8Array(buffer, 20, jsonLength));
  } catch (e) {
    fail(name, 'invalid glTF JSON (not UTF-8)');
  }
  return { json, bin, length };
}

/** jsonNestingDepth: the deepest nesting of arrays and objects (brackets in strings ignored). */
function nestingDepth(text, stopAt) {
  let depth = 0, deepest = 0, inString = false;
  for (let i = 0; i < text.length; ++i) {
    const c = text[i];
    if (inString) {
      if (c === '\\') ++i;
      else if (c === '"') inString = false;
    } else if (c === '"') inString = true;
    else if (c === '[' || c === '{') {
      deepest = Math.max(deepest, ++depth);
      if (deepest > stopAt) break;
    } else if (c === ']' || c === '}') --depth;
  }
  return deepest;
}

/** The glTF JSON of a GLB, parsed as decodeBake parses it (nesting first). */
function parseGlbJson(text, name) {
  if (nestingDepth(text, bakeFile.maxNesting) > bakeFile.maxNesting)
    fail(name, `JSON nested deeper than ${bakeFile.maxNesting} levels (PRT_MAX_NESTING)`);
  let gltf;
  try {
    gltf = JSON.parse(text);
  } catch (e) {
    fail(name, `invalid glTF JSON (${String(e.message).split('\n')[0].slice(0, 160)})`);
  }
  if (!gltf || typeof gltf !== 'object' || Array.isArray(gltf)) fail(name, 'invalid glTF: the JSON is not an object');
  return gltf;
}

const isObject = (o) => o !== null && typeof o === 'object' && !Array.isArray(o);
const has = (o, key) => isObject(o) && o[key] !== undefined && o[key] !== null;

/** schema::Reader: members read with a check each, failures naming the member. */
function reader(name) {
  const r = {
    fail: (what) => fail(name, what),
    member(o, key, where) {
      if (!has(o, key)) r.fail(`${where} has no '${key}'`);
      return o[key];
    },
    integer(o, key, where, lo, hi) {
      const v = r.member(o, key, where);
      let n;
      if (typeof v === 'string' && /^[0-9]{1,20}$/.test(v)) n = Number(v);
      else if (typeof v === 'number' && Number.isInteger(v) && v >= 0) n = v;
      else r.fail(`${where}.${key} = ${JSON.stringify(v)} is not a non-negative integer`);
      if (n < lo || n > hi) r.fail(`${where}.${key} = ${n} is out of range`);
      return n;
    },
    string(o, key, where) {
      const v = r.member(o, key, where);
      if (typeof v !== 'string') r.fail(`${where}.${key} is not a string`);
      return v;
    },
  };
  return r;
}

/** gltf::AccessorReader over the JSON and the BIN chunk: exact(index, components,
 *  componentType, count, what) checks an accessor as spanExact does and returns its elements
 *  (tightly packed: Float32Array, Uint32Array, Uint16Array, Int16Array or Uint8Array). */
function accessorReader(gltf, bin, name) {
  const nonNegative = (o, key, where, fallback) => {
    if (o[key] === undefined) return fallback;
    if (!(Number.isInteger(o[key]) && o[key] >= 0)) fail(name, `${where}.${key} is not a non-negative integer`);
    return o[key];
  };
  const array = (key) => {
    if (gltf[key] === undefined) return [];
    if (!Array.isArray(gltf[key])) fail(name, `${key} is not an array`);
    return gltf[key];
  };
  const accessors = array('accessors').map((a, i) => {
    const where = `accessors[${i}]`;
    if (!isObject(a)) fail(name, `${where} is not an object`);
    if (a.type !== undefined && typeof a.type !== 'string') fail(name, `${where}.type is not a string`);
    if (a.normalized !== undefined && typeof a.normalized !== 'boolean') fail(name, `${where}.normalized is not a boolean`);
    return { bufferView: nonNegative(a, 'bufferView', where, -1), byteOffset: nonNegative(a, 'byteOffset', where, 0),
             count: nonNegative(a, 'count', where, 0), componentType: nonNegative(a, 'componentType', where, 0),
             type: a.type || '', normalized: !!a.normalized, sparse: a.sparse !== undefined };
  });
  const views = array('bufferViews').map((v, i) => {
    const where = `bufferViews[${i}]`;
    if (!isObject(v)) fail(name, `${where} is not an object`);
    return { buffer: nonNegative(v, 'buffer', where, -1), byteOffset: nonNegative(v, 'byteOffset', where, 0),
             byteLength: nonNegative(v, 'byteLength', where, 0), byteStride: nonNegative(v, 'byteStride', where, 0) };
  });
  // Buffer 0 is the BIN chunk unless it names a file; a bake refers to nothing else.
  const buffers = array('buffers').map((b, i) => (i === 0 && !(isObject(b) && b.uri !== undefined) && bin ? bin : new Uint8Array(0)));
  const accessorAt = (index, what) => {
    if (!(Number.isInteger(index) && index >= 0 && index < accessors.length))
      fail(name, `${what}: accessor ${index} does not exist (the file has ${accessors.length})`);
    const a = accessors[index];
    if (a.sparse) fail(name, `${what}: sparse accessors are not supported`);
    return a;
  };
  const viewBytes = (index, what) => {
    const v = views[index];
    if (!v) fail(name, `${what}: bufferView ${index} does not exist (the file has ${views.length})`);
    const buf = buffers[v.buffer];
    if (!buf) fail(name, `${what}: bufferView ${index} has no valid buffer`);
    if (v.byteOffset > buf.length || v.byteLength > buf.length - v.byteOffset)
      fail(name, `${what}: bufferView ${index} (${v.byteLength} bytes at ${v.byteOffset}) lies outside its buffer of ${buf.length} bytes (truncated file?)`);
    return { bytes: buf, at: v.byteOffset, length: v.byteLength, stride: v.byteStride };
  };
  const exact = (index, components, componentType, count, what) => {
    const a = accessorAt(index, what);
    if (a.type !== kVectorType[components] || a.componentType !== componentType || a.normalized)
      fail(name, `${what}: accessor ${index} is ${a.type} of ${kComponentName[a.componentType] || a.componentType}${a.normalized ? ' (normalized)' : ''}, expected ${kVectorType[components]} of ${kComponentName[componentType]}`);
    if (a.count !== count) fail(name, `${what}: accessor ${index} has ${a.count} elements, expected ${count}`);
    const size = kComponentBytes[componentType], elem = size * components;
    const v = viewBytes(a.bufferView, what);
    const stride = v.stride || elem, n = a.count, len = v.length;
    if (stride < elem) fail(name, `${what}: byteStride ${stride} is smaller than an element (${elem} bytes)`);
    if (n > len) fail(name, `${what}: accessor count ${n} exceeds the ${len} bytes of its bufferView`);
    if (n > 0 && (a.byteOffset > len || n - 1 > Math.floor((len - a.byteOffset) / stride) || elem > len - a.byteOffset - (n - 1) * stride))
      fail(name, `${what}: accessor ${index} (${n} elements of ${elem} bytes, stride ${stride}, at ${a.byteOffset}) runs past its bufferView of ${len} bytes`);
    const out = new ({ [kFloat]: Float32Array, [kUint]: Uint32Array, [kUshort]: Uint16Array, [kShort]: Int16Array,
                       [kUbyte]: Uint8Array })[componentType](n * components);
    const d = new DataView(v.bytes.buffer, v.bytes.byteOffset + v.at, len);
    const get = { [kFloat]: (o) => d.getFloat32(o, true), [kUint]: (o) => d.getUint32(o, true),
                  [kUshort]: (o) => d.getUint16(o, true), [kShort]: (o) => d.getInt16(o, true),
                  [kUbyte]: (o) => d.getUint8(o) }[componentType];
    for (let i = 0; i < n; ++i)
      for (let c = 0; c < components; ++c) out[i * components + c] = get(a.byteOffset + i * stride + c * size);
    return out;
  };
  const count = (index, what) => accessorAt(index, what).count;
  return { exact, count, viewBytes };
}

function requireFinite(x, what, r) {
  for (let i = 0; i < x.length; ++i) if (!Number.isFinite(x[i])) r.fail(`${what} holds a non-finite value at element ${i}`);
}

/** io::decodeMesh and checkMeshExtent: each glTF mesh one triangle primitive with finite
 *  POSITION and NORMAL, uint32 indices inside the part, TEXCOORD_0 / COLOR_0 in every part or
 *  none, the lightmap set finite and (per-texel) inside [0, 1]², the totals the bake's. */
function checkMesh(gltf, ar, V, T, lightmap, perTexel, r) {
  const textureSet = lightmap === 0 ? '' : 'TEXCOORD_0', lightmapSet = lightmap < 0 ? '' : `TEXCOORD_${lightmap}`;
  if (!Array.isArray(gltf.meshes) || gltf.meshes.length === 0) r.fail('holds no mesh');
  let vertices = 0, triangles = 0, anyUv = false, anyColour = false;
  gltf.meshes.forEach((gm, mi) => {
    const what = `mesh ${mi} ('${isObject(gm) && typeof gm.name === 'string' ? gm.name.slice(0, 60) : ''}')`;
    if (!isObject(gm) || !Array.isArray(gm.primitives) || gm.primitives.length !== 1) r.fail(`${what} does not hold exactly one primitive`);
    const p = gm.primitives[0];
    if (!isObject(p)) r.fail(`${what}'s primitive is not an object`);
    if (p.mode !== undefined && p.mode !== 4) r.fail(`${what} is not a triangle list`);
    const attributes = r.member(p, 'attributes', what);
    const attr = (key) => {
      if (!isObject(attributes) || attributes[key] === undefined) return -1;
      if (!(Number.isInteger(attributes[key]) && attributes[key] >= 0 && attributes[key] <= 2147483647)) r.fail(`${what} attribute ${key} is not an accessor index`);
      return attributes[key];
    };
    if (attr('POSITION') < 0) r.fail(`${what} has no POSITION`);
    const n = ar.count(attr('POSITION'), `${what} POSITION`);
    if (n === 0 || vertices + n > V) r.fail(`${what} has more vertices than the bake's vertexCount`);
    const pos = ar.exact(attr('POSITION'), 3, kFloat, n, `${what} POSITION`);
    const nrm = ar.exact(attr('NORMAL'), 3, kFloat, n, `${what} NORMAL`);
    requireFinite(pos, `${what} POSITION`, r);
    requireFinite(nrm, `${what} NORMAL`, r);
    for (let i = 0; i < pos.length; ++i)
      if (Math.abs(pos[i]) > bakeFile.maxCoordinate)
        r.fail(`vertex ${vertices + Math.floor(i / 3)} lies outside the extent the ray tracer handles (|coordinate| <= ${bakeFile.maxCoordinate}, PRT_MAX_COORDINATE); rescale the scene`);
    const hasUv = textureSet !== '' && attr(textureSet) >= 0, hasColour = attr('COLOR_0') >= 0;
    if (mi > 0 && (hasUv !== anyUv || hasColour !== anyColour)) r.fail(`${what} differs from the first part in TEXCOORD_0/COLOR_0`);
    anyUv = hasUv, anyColour = hasColour;
    if (hasUv) ar.exact(attr('TEXCOORD_0'), 2, kFloat, n, `${what} TEXCOORD_0`);
    if (lightmapSet) {
      if (attr(lightmapSet) < 0) r.fail(`${what} has no ${lightmapSet} (lightmapTexCoord names it)`);
      const uv = ar.exact(attr(lightmapSet), 2, kFloat, n, `${what} ${lightmapSet}`);
      requireFinite(uv, `${what} ${lightmapSet}`, r);
      // geometry::firstUvOutside, its bounds generated from the library.
      if (perTexel)
        for (let i = 0; i < uv.length; ++i)
          if (uv[i] < bakeFile.lightmapUvMin || uv[i] > bakeFile.lightmapUvMax)
            r.fail(`the lightmap UV of vertex ${vertices + (i >> 1)} is (${uv[i & ~1]}, ${uv[i | 1]}), outside [0, 1]^2 (a per-texel bake's UVs lie inside it)`);
    }
    if (hasColour) requireFinite(ar.exact(attr('COLOR_0'), 3, kFloat, n, `${what} COLOR_0`), `${what} COLOR_0`, r);
    if (!(Number.isInteger(p.indices) && p.indices >= 0 && p.indices <= 2147483647)) r.fail(`${what} has no indices`);
    const ni = ar.count(p.indices, `${what} indices`);
    if (ni === 0 || ni % 3 !== 0) r.fail(`${what}: index count ${ni} is not a positive multiple of 3`);
    if (triangles + ni / 3 > T) r.fail(`${what} has more triangles than the bake's triangleCount`);
    const idx = ar.exact(p.indices, 1, kUint, ni, `${what} indices`);
    for (let i = 0; i < ni; ++i)
      if (idx[i] >= n) r.fail(`${what}: triangle ${Math.floor(i / 3)} references vertex ${idx[i]} (part has ${n})`);
    vertices += n, triangles += ni / 3;
  });
  if (vertices !== V || triangles !== T)
    r.fail(`the meshes hold ${vertices} vertices and ${triangles} triangles, the bake says ${V} and ${T}`);
}

/** io::decodeBaseColour's layout: one embedded PNG shown by texture 0 as material 0's
 *  baseColorTexture on TEXCOORD_0 (its pixels are GLTFLoader's to decode). */
function checkBaseColour(gltf, ar, r) {
  const listed = (key) => (Array.isArray(gltf[key]) ? gltf[key].length : 0);
  const pbr = listed('materials') > 0 && isObject(gltf.materials[0]) ? gltf.materials[0].pbrMetallicRoughness : null;
  const texture = isObject(pbr) && pbr.baseColorTexture !== undefined ? pbr.baseColorTexture : null;
  if (!texture && listed('images') === 0 && listed('textures') === 0) return;
  if (!texture || listed('images') !== 1 || listed('textures') !== 1)
    r.fail('holds images or textures other than one base colour texture of material 0 (it is not a prtkit bake, or was edited)');
  if (r.integer(texture, 'index', 'materials[0] baseColorTexture', 0, 0) !== 0 ||
      (has(texture, 'texCoord') && r.integer(texture, 'texCoord', 'materials[0] baseColorTexture', 0, 0) !== 0) ||
      r.integer(gltf.textures[0], 'source', 'textures[0]', 0, 0) !== 0)
    r.fail('the base colour texture is not texture 0 on TEXCOORD_0 showing image 0');
  const img = gltf.images[0];
  if (has(img, 'uri')) r.fail('refers to an external image; a bake is one .glb');
  if (!has(img, 'mimeType') || img.mimeType !== 'image/png') r.fail('the base colour texture is not an embedded PNG (mimeType image/png)');
  ar.viewBytes(r.integer(img, 'bufferView', 'images[0]', 0, 2147483647), 'the base colour texture');
}

/** The transfers' rows as transfer_codecs.cpp decodes them: dense vectors per vertex as
 *  ⌈S/4⌉ VEC4 float columns, other dense rows one SCALAR float accessor, CPCA four (two
 *  without a basis) with ids below K; every value finite. */
function checkTransfers(prt, where, version, domain, rows, ar, r) {
  if (prt.transfers === undefined) return 0;
  if (!Array.isArray(prt.transfers)) r.fail(`${where}.transfers is not an array`);
  const seen = new Set();
  prt.transfers.forEach((t, ti) => {
    const tw = `${where}.transfers[${ti}]`;
    if (!isObject(t)) r.fail(`${tw} is not an object`);
    const sw = `${tw}.settings`, s = r.member(t, 'settings', tw);
    if (!isObject(s)) r.fail(`${sw} is not an object`);
    const mode = r.string(s, 'mode', sw);
    if (!modes.some((m) => m.name === mode)) r.fail(`${sw}: unknown transfer mode '${mode}'`);
    r.string(s, 'sampling', sw);
    r.integer(s, 'samples', sw, 1, bakeFile.maxBakeSamples);
    r.integer(s, 'bounces', sw, 0, bakeFile.maxBounces);
    r.integer(s, 'seed', sw, 0, 18446744073709551615);
    // Adaptive sampling's target (checkRecipe): a number in [0, 1] when present.
    if (has(s, 'targetError') && !(typeof s.targetError === 'number' && s.targetError >= 0 && s.targetError <= 1))
      r.fail(`${sw}.targetError = ${JSON.stringify(s.targetError)} is not a number in [0, 1]`);
    const layout = has(s, 'layout') ? r.string(s, 'layout', sw) : layouts[0];
    if (!layouts.includes(layout)) r.fail(`${sw}: unknown layout '${layout}'`);
    if (layout === 'matrix' && version < 2) r.fail(`${sw} is a matrix transfer in a version ${version} file (matrices need version 2)`);
    const d = has(s, 'domain') ? r.string(s, 'domain', sw) : domains[0];
    if (!domains.includes(d)) r.fail(`${sw}: unknown domain '${d}'`);
    const basis = has(s, 'basis') ? r.string(s, 'basis', sw) : 'sh';
    if (basis !== 'sh' && basis !== 'haar') r.fail(`${sw}: unknown basis '${basis}' (expected sh or haar)`);
    const sameMode = () => {
      if (d !== domain) r.fail(`${sw}.domain is ${d} in a bake over ${domain}`);
      if (seen.has(`${mode} ${layout}`)) r.fail(`two ${layout} transfers of mode ${mode}`);
      seen.add(`${mode} ${layout}`);
    };
    // Haar-wavelet transfer (format 8): its own shape and quantised rows (haar_bake.js).
    if (basis === 'haar') {
      checkHaarTransfer(t, s, tw, sw, version, layout, d, rows, ar, r);
      sameMode();
      return;
    }
    const B = r.integer(s, 'bands', sw, 1, kBandsMaxLibrary), C = r.integer(s, 'channels', sw, 1, 3);
    if (C === 2) r.fail(`${sw}.channels must be 1 or 3`);
    if (domain === domains[2] && layout !== 'matrix') r.fail(`${tw} is a ${layout} transfer over probes (a probe holds a matrix)`);
    sameMode();
    const S = (layout === 'matrix' ? B ** 4 : B * B) * C, n = rows;
    const list = (want, what) => {
      const acc = r.member(t, 'accessors', tw);
      if (!Array.isArray(acc) || acc.length !== want) r.fail(`${tw}.accessors must list ${want} accessors for ${what}`);
      acc.forEach((i, k) => { if (!(Number.isInteger(i) && i >= 0 && i <= 2147483647)) r.fail(`${tw}.accessors[${k}] is not an index`); });
      return acc;
    };
    const floats = (index, count, what) => {
      const x = ar.exact(index, 1, kFloat, count, what);
      requireFinite(x, what, r);
      return x;
    };
    if (has(t, 'compressed')) {
      if (version < 3) r.fail(`${tw} is compressed transfer in a version ${version} file (compression needs version 3)`);
      const zw = `${tw}.compressed`, z = t.compressed;
      if (!isObject(z) || r.string(z, 'method', zw) !== 'cpca') r.fail(`${zw}.method must be "cpca"`);
      const K = r.integer(z, 'clusters', zw, 1, Math.min(n, 2147483647)), N = r.integer(z, 'basisCount', zw, 0, S);
      const acc = list(N > 0 ? 4 : 2, `compressed transfer with ${N} basis vectors`);
      const what = `${mode} compressed transfer`;
      const ids = K <= 65536 ? ar.exact(acc[0], 1, kUshort, n, `${what} cluster ids`) : ar.exact(acc[0], 1, kUint, n, `${what} cluster ids`);
      let next = 1;
      if (N > 0) floats(acc[next++], n * N, `${what} weights`);
      floats(acc[next++], K * S, `${what} means`);
      if (N > 0) floats(acc[next++], K * N * S, `${what} basis`);
      for (let v = 0; v < n; ++v) if (ids[v] >= K) r.fail(`${zw}: row ${v} names cluster ${ids[v]} of ${K}`);
    } else if (layout === 'matrix' || domain === 'texels') {
      const what = layout === 'matrix' ? ' matrices' : ' texel rows';
      floats(list(1, `the${what}`)[0], n * S, `${mode}${what}`);
    } else {
      const K = Math.ceil(S / 4), acc = list(K, `${B} bands x ${C} channels`);
      acc.forEach((index, k) => requireFinite(ar.exact(index, 4, kFloat, n, `${mode} transfer column ${k}`), `${mode} transfer`, r));
    }
  });
  return prt.transfers.length;
}

/**
 * Checks a bake's glTF JSON (parsed) and BIN chunk (a Uint8Array or null) as io::decodeBake
 * does, before anything is built from them; throws one line naming the file (and the member).
 * Exported for readers that hold the parsed document (prtkit-three's plugin: parser.json and the
 * binary extension's body).
 */
export function checkBakeDocument(gltf, bin, name) {
  const r = reader(name);
  const objectAt = (parent, key) => {
    if (!isObject(gltf[parent]) || gltf[parent][key] === undefined) return null;
    if (!isObject(gltf[parent][key])) r.fail(`${parent}.${key} is not an object`);
    return gltf[parent][key];
  };
  const inExtension = objectAt('extensions', bakeFormat.extension), inExtras = objectAt('extras', 'prtkit');
  if (!inExtension && !inExtras)
    r.fail(`is a glTF file but not a prtkit bake (no ${bakeFormat.extension} extension; write one with prt bake)`);
  const prt = inExtension || inExtras, where = inExtension ? `extensions.${bakeFormat.extension}` : 'extras.prtkit';
  const version = r.integer(prt, 'formatVersion', where, 0, 1e9);
  if (version > bakeFormat.version)
    r.fail(`bake format version ${version} is newer than this page reads (${bakeFormat.version}; it reads versions ${bakeFormat.reads.join(', ')})`);
  if (inExtension && version < bakeFormat.firstExtensionVersion)
    r.fail(`${where}: format version ${version} predates the extension (versions 1-${bakeFormat.firstExtensionVersion - 1} live in extras.prtkit)`);
  if (!inExtension && version >= bakeFormat.firstExtensionVersion)
    r.fail(`extras.prtkit: format version ${version} belongs in the ${bakeFormat.extension} extension`);
  if (version < 1) r.fail(`bake format version ${version} is invalid`);
  const V = r.integer(prt, 'vertexCount', where, 1, 4294967295), T = r.integer(prt, 'triangleCount', where, 1, 4294967295);
  if (V > bakeFile.maxVertices) r.fail(`vertex count ${V} exceeds the limit of ${bakeFile.maxVertices} (PRT_MAX_VERTICES)`);
  if (T > bakeFile.maxTriangles) r.fail(`triangle count ${T} exceeds the limit of ${bakeFile.maxTriangles} (PRT_MAX_TRIANGLES)`);
  if (Array.isArray(gltf.buffers))
    for (const b of gltf.buffers) if (isObject(b) && b.uri !== undefined) r.fail(`refers to an external file (${String(b.uri).slice(0, 80)}); a bake is one .glb`);
  const ar = accessorReader(gltf, bin, name);
  const lightmap = has(prt, 'lightmapTexCoord') ? r.integer(prt, 'lightmapTexCoord', where, 0, 1) : -1;
  // The domain: the vertices, or the texels of one lightmap (format 6 on).
  let domain = domains[0], domainRows = V, rangeKey = 'vertexRange';
  if (has(prt, 'texelRange') || has(prt, 'lightmap')) {
    if (version < 6) r.fail(`${where} holds per-texel transfer in a version ${version} file (texels need version 6)`);
    if (has(prt, 'vertexRange')) r.fail(`${where} has both a vertexRange and a texelRange`);
    const lw = `${where}.lightmap`, lm = r.member(prt, 'lightmap', where);
    const W = r.integer(lm, 'width', lw, 1, maxLightmapSide), H = r.integer(lm, 'height', lw, 1, maxLightmapSide);
    r.integer(lm, 'padding', lw, 0, bakeFile.maxLightmapPadding);
    if (has(lm, 'seamsFixed') && typeof lm.seamsFixed !== 'boolean') r.fail(`${lw}.seamsFixed is not a boolean`);
    if (has(lm, 'denoised') && typeof lm.denoised !== 'boolean') r.fail(`${lw}.denoised is not a boolean`);
    if (lightmap < 0) r.fail(`${where} holds per-texel transfer but names no lightmapTexCoord (the UVs it is over)`);
    domain = domains[1], domainRows = W * H, rangeKey = 'texelRange';
  }
  // Or the probes of a grid in space (format 7 on; probe_bake.js).
  if (has(prt, 'probeRange') || has(prt, 'probeGrid')) {
    const grid = checkProbeGridDocument(prt, where, version, domain === domains[1], r);
    domain = domains[2], domainRows = probeCount(grid), rangeKey = 'probeRange';
  }
  checkMesh(gltf, ar, V, T, lightmap, domain === domains[1], r);
  checkBaseColour(gltf, ar, r);
  const rw = `${where}.${rangeKey}`, range = r.member(prt, rangeKey, where);
  const first = r.integer(range, 'first', rw, 0, 4294967295), count = r.integer(range, 'count', rw, 1, 4294967295);
  if (first + count > domainRows)
    r.fail(`${kRowName[domain]} range ${first}+${count} is outside the ${kExtent[domain](domainRows)}`);
  const transfers = checkTransfers(prt, where, version, domain, count, ar, r);
  if (transfers === 0 && (first !== 0 || count !== domainRows)) r.fail('a partial bake without transfers');
  if (transfers === 0 && domain === domains[1]) r.fail('a per-texel bake without transfers');
  if (transfers === 0 && domain === domains[2]) r.fail('a probe bake without transfers');
}

/** rowName and domainExtent (bake_file.cpp): what a row is, and where a range must lie. */
const kRowName = { [domains[0]]: 'vertex', [domains[1]]: 'texel', [domains[2]]: 'probe' };
const kExtent = { [domains[0]]: (n) => `mesh (${n} vertices)`, [domains[1]]: (n) => `lightmap (${n} texels)`,
                  [domains[2]]: (n) => `grid (${n} probes)` };

/** The binary chunk GLTFLoader holds for a parsed .glb (null for a .gltf). */
function binaryBody(parser) {
  const ext = parser.extensions && parser.extensions.KHR_binary_glTF;
  return ext && ext.body ? new Uint8Array(ext.body) : null;
}

/** `e` as an Error of one line starting with the file's name (readers' unforeseen failures, a
 *  library's raw errors, keep their first line). */
function named(e, name) {
  const line = String(e && e.message !== undefined ? e.message : e).split('\n')[0];
  return e instanceof Error && !String(e.message).includes('\n') && line.startsWith(`${name}: `) ? e : new Error(`${name}: ${line}`);
}

/**
 * Parses GLB bytes into a bake (readBake's result). `limits` = { maxTextureSize, maxBands };
 * `extras` as readBake's.
 */
export async function parseBake(buffer, name, limits, extras = {}) {
  if (!(buffer instanceof ArrayBuffer)) fail(name, 'is not a glTF binary (.glb) file (no bytes)');
  if (buffer.byteLength > bakeFile.maxFileBytes) fail(name, 'file too large (> 4 GiB)');
  // The container, the JSON and every accessor the bake uses are checked before GLTFLoader
  // builds anything from them (as decodeBake reads them: checkBakeDocument).
  const glb = splitGlb(buffer, name);
  checkBakeDocument(parseGlbJson(glb.json, name), glb.bin, name);
  let gltf;
  try {
    gltf = await new GLTFLoader().parseAsync(glb.length === buffer.byteLength ? buffer : buffer.slice(0, glb.length), '');
  } catch (e) {
    fail(name, `cannot be read as glTF (${String(e && e.message ? e.message : e).split('\n')[0]})`);
  }
  return readBake(gltf, name, limits, { ...extras, [kChecked]: true });
}

/** readBake's extras mark for a document parseBake has already checked. */
const kChecked = Symbol('checked');

/** A part's base-colour texture (glTF baseColorTexture, which GLTFLoader put on its material as
 *  `map`) sampled as prt render samples it (geometry/base_colour.hpp): sRGB decoded before
 *  bilinear filtering, repeat wrapping, no mipmaps, row 0 at v = 0 (GLTFLoader's flipY false);
 *  null without one. It multiplies the diffuse part per pixel at the part's TEXCOORD_0. */
function baseColourTexture(mesh, geometry, name) {
  const map = mesh.material && mesh.material.map;
  if (!map) return null;
  const uv = geometry.getAttribute('uv');
  if (!uv || uv.itemSize !== 2 || uv.count !== geometry.getAttribute('position').count)
    fail(name, `part '${mesh.name}' has a base-colour texture but no texture UVs (TEXCOORD_0) for it`);
  map.colorSpace = THREE.SRGBColorSpace;
  map.wrapS = map.wrapT = THREE.RepeatWrapping;
  map.minFilter = map.magFilter = THREE.LinearFilter;
  map.generateMipmaps = false;
  map.flipY = false;
  map.needsUpdate = true;
  return map;
}

/** The texels' points (render::packTexelPoints' twelve floats a row) as a data image of three
 *  texels a row, checked: one row per texel, finite. */
function texelPointsImage(x, rows, limits, name) {
  if (!(x instanceof Float32Array) || x.length !== rows * 12)
    fail(name, `its texel points hold ${x && x.length} floats, ${rows * 12} expected (twelve a texel of the lightmap)`);
  for (let i = 0; i < x.length; ++i) if (!Number.isFinite(x[i])) fail(name, `its texel points: value ${i} is not finite`);
  const img = textureShape(rows * 3, limits, name, 'the texels\' points');
  img.data.set(x);
  return img;
}

/** The bake's object in a parsed glTF's JSON: the PRTKIT_radiance_transfer extension (format
 *  5 on), else the root's extras.prtkit (formats 1-4); null when the asset is not a bake. */
export function bakeObject(json) {
  return (json.extensions && json.extensions[bakeFormat.extension]) || (json.extras && json.extras.prtkit) || null;
}

/**
 * Checks a document GLTFLoader has parsed (its `parser`; prtkit-three's plugin, in beforeRoot,
 * before GLTFLoader builds the scene from it) as parseBake checks one before parsing: the JSON
 * text's nesting, then checkBakeDocument. Throws an Error of one line starting with `name`.
 */
export function checkParsedBake(parser, name) {
  try {
    const text = parser.extensions && parser.extensions.KHR_binary_glTF && parser.extensions.KHR_binary_glTF.content;
    if (typeof text === 'string' && nestingDepth(text, bakeFile.maxNesting) > bakeFile.maxNesting)
      fail(name, `JSON nested deeper than ${bakeFile.maxNesting} levels (PRT_MAX_NESTING)`);
    checkBakeDocument(parser.json, binaryBody(parser), name);
  } catch (e) {
    throw named(e, name);
  }
}

/**
 * Reads the bake in GLTFLoader's result `gltf` (the page's parse, or the three.js module's
 * loader plugin) into { name, parts: [{ mesh (GLTFLoader's), geometry, name, first, vertices,
 * hasAlbedo, baseColour (a THREE.Texture or null), texels: { transfer key → { data, width, height } } }], transfers (in the library's
 * preference order: [{ key, mode, layout, bands, channels, path, texelsPerRow, compressed,
 * response, recipeMaterial, perPixel, lightmap }]), lightmap ({ width, height } of a per-texel
 * bake, else null), maxBands, vertices, triangles, centre, radius }. The parts' transfer
 * attributes move into the texels (and are deleted from the geometry); a per-texel bake's rows
 * are one image every part shares, its lightmap UVs the attribute prtLightmapUv.
 * extras.texelPoints: per-texel glossy matrices' points (a Float32Array of W·H rows of twelve
 * floats, render::packTexelPoints: position, normal, albedo, each padded to four), which prt web
 * writes beside its own bake; the bake then carries them as the data image texelPoints (three
 * texels a row, shaders/prt_lightmap.glsl's uPoints). Without them such matrices are refused.
 */
export async function readBake(gltf, name, limits, extras = {}) {
  try {
    if (!extras[kChecked]) checkParsedBake(gltf.parser, name);
    return await readCheckedBake(gltf, name, limits, extras);
  } catch (e) {
    throw named(e, name);
  }
}

async function readCheckedBake(gltf, name, limits, extras) {
  const json = gltf.parser.json;
  // The bake's object: the PRTKIT_radiance_transfer extension (format 5 on), else the root's
  // extras.prtkit (formats 1-4).
  const prt = bakeObject(json);
  if (!prt) fail(name, `is a glTF file but not a prtkit bake (no ${bakeFormat.extension} extension; write one with prt bake)`);
  if (!bakeFormat.reads.includes(prt.formatVersion))
    fail(name, `bake format version ${prt.formatVersion} is not supported by this page (it reads versions ${bakeFormat.reads.join(', ')})`);
  const entries = Array.isArray(prt.transfers) ? prt.transfers : [];
  if (entries.length === 0) fail(name, 'the bake holds no transfer (bake it with prt bake --mode ...)');
  // A probe grid: the light arriving at points in space, relit on the CPU (probe_bake.js).
  if (prt.probeGrid) return readProbeBake(gltf, prt, name);
  // Haar wavelets: relit on the CPU (per vertex, or per texel) under a light turned from the
  // environment's cube.
  if (entries.some(isHaarEntry)) return readHaarBake(gltf, prt, name, extras);
  // The domain: the vertices, or the texels of one lightmap (relit per pixel); whole.
  const domain = rowDomain(prt, name), { lightmap, rowCount } = domain;

  const points = lightmap && extras.texelPoints ? texelPointsImage(extras.texelPoints, rowCount, limits, name) : null;
  const read = [];
  for (const e of entries) {
    const t = await readTransfer(gltf, e, rowCount, name, limits, lightmap, !!points);
    t.key = `${t.mode} ${t.layout}`;
    if (read.some((u) => u.key === t.key)) fail(name, `holds two ${t.key} transfers`);
    read.push(t);
  }
  const transfers = preferenceOrder(read);
  const glossy = transfers.some((t) => t.matrix);

  const mesh = meshParts(gltf, prt, name);
  const parts = mesh.parts.map((p) => {
    const g = p.geometry, m = p.mesh;
    const part = { ...p, baseColour: baseColourTexture(m, g, name), texels: {} };
    for (const t of transfers) part.texels[t.key] = packRows(t, part, limits, name);
    // Per-texel transfer: the lightmap UVs, under the name the lightmap stage reads.
    useLightmapUvs(p, domain, prt, name);
    // Normals stay for glossy matrices (the lobe about the reflected view), the lightmap UVs for
    // per-texel transfer; the rest goes.
    const keep = ['position', 'color'].concat(glossy ? ['normal'] : [], lightmap ? ['prtLightmapUv'] : [],
                                              part.baseColour ? ['uv'] : []);
    for (const a of Object.keys(g.attributes)) if (!keep.includes(a)) g.deleteAttribute(a);
    if (glossy && !g.getAttribute('normal')) fail(name, `part '${m.name}' has no normals (glossy transfer needs them)`);
    return part;
  });
  const { vertices, triangles, centre, radius } = mesh;
  return { name, parts, transfers, lightmap, texelPoints: transfers.some((t) => t.perPixel && t.matrix) ? points : null,
           maxBands: Math.max(...transfers.map((t) => t.bands)),
           vertices, triangles, centre, radius };
}

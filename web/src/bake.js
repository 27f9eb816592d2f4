// Reading a prtkit bake (.glb, docs/formats-bake.md) in the page: three.js's GLTFLoader parses
// the glTF (it keeps the custom `_PRT_<MODE>_T<k>` VEC4 attributes, lower-cased), this file
// checks the container and the mesh (the domain: every vertex, or every texel of a lightmap over
// the mesh's lightmap UVs, relit per pixel), and every transfer goes through the one reader
// (transfer.js). Every problem is an Error with one line naming the file; nothing here touches
// the scene. tests/web/golden_check.mjs checks the texels, the pick order and the framing
// against the library (relight::packShaderRows, io::transferPreference, render::meshFraming).
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

import { bakeFormat, maxLightmapSide } from 'prt:constants';
import { packRows, preferenceOrder, readTransfer } from './transfer.js';
import { textureShape } from './texels.js';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/**
 * Parses GLB bytes into a bake (readBake's result). `limits` = { maxTextureSize, maxBands };
 * `extras` as readBake's.
 */
export async function parseBake(buffer, name, limits, extras = {}) {
  if (!(buffer instanceof ArrayBuffer) || buffer.byteLength < 20)
    fail(name, 'is not a glTF binary (.glb) file (too short)');
  const head = new DataView(buffer);
  if (head.getUint32(0, true) !== 0x46546c67)  // "glTF"
    fail(name, 'is not a glTF binary (.glb) file (no glTF magic)');
  if (head.getUint32(8, true) !== buffer.byteLength)
    fail(name, `is truncated or padded: the header says ${head.getUint32(8, true)} bytes, the file has ${buffer.byteLength}`);
  let gltf;
  try {
    gltf = await new GLTFLoader().parseAsync(buffer, '');
  } catch (e) {
    fail(name, `cannot be read as glTF (${String(e && e.message ? e.message : e).split('\n')[0]})`);
  }
  return readBake(gltf, name, limits, extras);
}

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
  const json = gltf.parser.json;
  // The bake's object: the PRTKIT_radiance_transfer extension (format 5 on), else the root's
  // extras.prtkit (formats 1-4).
  const prt = bakeObject(json);
  if (!prt) fail(name, `is a glTF file but not a prtkit bake (no ${bakeFormat.extension} extension; write one with prt bake)`);
  if (!bakeFormat.reads.includes(prt.formatVersion))
    fail(name, `bake format version ${prt.formatVersion} is not supported by this page (it reads versions ${bakeFormat.reads.join(', ')})`);
  const entries = Array.isArray(prt.transfers) ? prt.transfers : [];
  if (entries.length === 0) fail(name, 'the bake holds no transfer (bake it with prt bake --mode ...)');
  // The domain: the vertices, or the texels of one lightmap over the mesh's lightmap UVs (format
  // 6; relit per pixel). Either must be complete.
  let lightmap = null, rowCount = prt.vertexCount, uvName = null;
  if (prt.texelRange || prt.lightmap) {
    const lm = prt.lightmap || {}, range = prt.texelRange || {};
    if (!(Number.isInteger(lm.width) && Number.isInteger(lm.height) && lm.width >= 1 && lm.height >= 1 && lm.width <= maxLightmapSide && lm.height <= maxLightmapSide))
      fail(name, `holds per-texel transfer over a lightmap of ${lm.width} x ${lm.height} texels (1..${maxLightmapSide} a side expected)`);
    lightmap = { width: lm.width, height: lm.height };
    rowCount = lm.width * lm.height;
    if (range.first !== 0 || range.count !== rowCount)
      fail(name, `holds transfer for texels ${range.first}..${range.first + range.count} of ${rowCount} only (merge the pieces with prt merge first)`);
    const set = prt.lightmapTexCoord;
    if (!(Number.isInteger(set) && set >= 0 && set <= 3))
      fail(name, `holds per-texel transfer but names no lightmapTexCoord (0..3) it is over`);
    uvName = set === 0 ? 'uv' : `uv${set}`;  // GLTFLoader's names of TEXCOORD_n
  } else {
    const range = prt.vertexRange || {};
    if (range.first !== 0 || range.count !== prt.vertexCount)
      fail(name, `holds transfer for vertices ${range.first}..${range.first + range.count} of ${prt.vertexCount} only (merge the pieces with prt merge first)`);
  }

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

  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  if (meshes.length === 0) fail(name, 'holds no triangle mesh');
  const parts = [];
  let vertices = 0, triangles = 0;
  const lo = new THREE.Vector3(Infinity, Infinity, Infinity), hi = lo.clone().negate();
  for (const m of meshes) {
    const g = m.geometry;
    const pos = g.getAttribute('position');
    if (!pos || !g.index) fail(name, `part '${m.name}' has no positions or indices`);
    const V = pos.count;
    vertices += V;
    triangles += g.index.count / 3;
    g.computeBoundingBox();
    lo.min(g.boundingBox.min);
    hi.max(g.boundingBox.max);
    // The part's first vertex in the file's (global) order: its POSITION window's offset.
    const assoc = gltf.parser.associations.get(m);
    const posAccessor = assoc && json.meshes[assoc.meshes].primitives[assoc.primitives || 0].attributes.POSITION;
    const first = posAccessor !== undefined ? (json.accessors[posAccessor].byteOffset || 0) / 12 : -1;
    if (!(first >= 0 && first + V <= prt.vertexCount)) fail(name, `part '${m.name}' has no place in the vertex order`);
    const part = { mesh: m, geometry: g, name: m.name, first, vertices: V, hasAlbedo: !!g.getAttribute('color'),
                   baseColour: baseColourTexture(m, g, name), texels: {} };
    for (const t of transfers) part.texels[t.key] = packRows(t, part, limits, name);
    // Per-texel transfer: the lightmap UVs, under the name the lightmap stage reads.
    if (lightmap) {
      const uv = g.getAttribute(uvName);
      if (!uv || uv.itemSize !== 2 || uv.count !== V)
        fail(name, `part '${m.name}' has no lightmap UVs (TEXCOORD_${prt.lightmapTexCoord}), which its per-texel transfer is over`);
      g.setAttribute('prtLightmapUv', uv);
    }
    // Normals stay for glossy matrices (the lobe about the reflected view), the lightmap UVs for
    // per-texel transfer; the rest goes.
    const keep = ['position', 'color'].concat(glossy ? ['normal'] : [], lightmap ? ['prtLightmapUv'] : [],
                                              part.baseColour ? ['uv'] : []);
    for (const a of Object.keys(g.attributes)) if (!keep.includes(a)) g.deleteAttribute(a);
    if (glossy && !g.getAttribute('normal')) fail(name, `part '${m.name}' has no normals (glossy transfer needs them)`);
    parts.push(part);
  }
  if (vertices !== prt.vertexCount) fail(name, `has ${vertices} vertices but extras.prtkit says ${prt.vertexCount}`);
  // render::meshFraming: the box's centre, radius to the farthest vertex.
  const centre = lo.clone().add(hi).multiplyScalar(0.5);
  let r2 = 0;
  for (const p of parts) {
    const pos = p.geometry.getAttribute('position');
    for (let v = 0; v < pos.count; ++v) {
      const dx = pos.getX(v) - centre.x, dy = pos.getY(v) - centre.y, dz = pos.getZ(v) - centre.z;
      r2 = Math.max(r2, dx * dx + dy * dy + dz * dz);
    }
  }
  return { name, parts, transfers, lightmap, texelPoints: transfers.some((t) => t.perPixel && t.matrix) ? points : null,
           maxBands: Math.max(...transfers.map((t) => t.bands)),
           vertices, triangles, centre, radius: Math.max(Math.sqrt(r2), 1e-6) };
}

// A relit lightmap in three.js (docs/three.md, "Relit lightmaps"): the glTF that `prt export
// BAKE --format lightmap | lightmap-sh -o NAME.glb` writes — the bake's mesh and, at the glTF
// root, the extension PRTKIT_lightmap (docs/extensions/PRTKIT_lightmap, io/lightmap_gltf.hpp):
// the lightmap's size, its UV set (`texCoord`) and named layers, each a FLOAT VEC3 accessor of
// W × H texels, row-major, row 0 at v = 0 (glTF's, and three.js's for glTF textures: flipY off).
//
// Every layer becomes a DataTexture on request. A plain lightmap (kind "lightmap": its one layer
// f = E/π, the exit radiance of a white Lambertian surface) is what three.js's lightMap reads as
// irradiance once multiplied by π — its shaders add lightMap · lightMapIntensity to the
// irradiance and shade it with BRDF_Lambert = albedo/π (lights_fragment_maps.glsl,
// RE_IndirectDiffuse_Physical) — so applyTo() sets lightMapIntensity = π. The SH layers of
// kind "lightmap-sh" (L0, L1x, L1y, L1z, zonal, axis, or sh0..sh8) have no three.js slot: they
// come as textures for the app's own shader, decoded as the extension's `decode` says.
import * as THREE from 'three';

const kExtension = 'PRTKIT_lightmap';
const kMaxSide = 16384;  // prt bake's largest lightmap (--resolution)

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/** A lightmap read from a glTF: its description and layers (Float32Array, 3 floats a texel). */
export class PRTLightmap {
  constructor(description, layers, name) {
    this.name = name;
    this.kind = description.kind;
    this.encoding = description.encoding || null;
    this.width = description.lightmap.width;
    this.height = description.lightmap.height;
    this.texCoord = description.lightmap.texCoord;
    this.description = description;
    this.layers = layers;
    this.textures = new Map();
  }

  /** Layer `layer` ('f', 'L0', ...) as an RGBA half-float DataTexture (filterable everywhere),
   *  linear, on the lightmap's UV set (texture.channel); made once. */
  texture(layer) {
    const values = this.layers.get(layer);
    if (!values) fail(this.name, `no lightmap layer '${layer}' (it holds ${[...this.layers.keys()].join(', ')})`);
    if (this.textures.has(layer)) return this.textures.get(layer);
    const texels = this.width * this.height, data = new Uint16Array(4 * texels);
    const one = THREE.DataUtils.toHalfFloat(1);
    for (let t = 0; t < texels; ++t) {
      for (let c = 0; c < 3; ++c) data[4 * t + c] = THREE.DataUtils.toHalfFloat(values[3 * t + c]);
      data[4 * t + 3] = one;
    }
    const tex = new THREE.DataTexture(data, this.width, this.height, THREE.RGBAFormat, THREE.HalfFloatType);
    tex.colorSpace = THREE.LinearSRGBColorSpace;
    tex.magFilter = tex.minFilter = THREE.LinearFilter;
    tex.flipY = false;
    tex.channel = this.texCoord;
    tex.name = `${kExtension} ${layer}`;
    tex.needsUpdate = true;
    this.textures.set(layer, tex);
    return tex;
  }

  /** Gives every mesh under `root` whose material takes a lightMap (MeshStandardMaterial,
   *  MeshLambertMaterial, ...) this plain lightmap: lightMap = f, lightMapIntensity = π (f is
   *  E/π; three.js's lightMap is irradiance). Throws for an SH lightmap, or a mesh without the
   *  UV set. Returns the meshes given it. */
  applyTo(root) {
    if (this.kind !== 'lightmap')
      fail(this.name, `holds a ${this.kind} (${this.encoding}) lightmap: three.js's lightMap takes one RGB layer; decode the SH layers in your own shader (their decode is in .description.decode) or export --format lightmap`);
    const tex = this.texture('f'), uv = this.texCoord === 0 ? 'uv' : `uv${this.texCoord}`, given = [];
    root.traverse((o) => {
      if (!o.isMesh || !o.material || !('lightMap' in o.material)) return;
      if (!o.geometry.getAttribute(uv)) fail(this.name, `mesh '${o.name}' lacks the lightmap's UV set TEXCOORD_${this.texCoord}`);
      o.material.lightMap = tex;
      o.material.lightMapIntensity = Math.PI;
      o.material.needsUpdate = true;
      given.push(o);
    });
    return given;
  }

  /** Frees the textures made. */
  dispose() {
    for (const t of this.textures.values()) t.dispose();
    this.textures.clear();
  }
}

/**
 * Reads PRTKIT_lightmap from `gltf` (GLTFLoader's result) and resolves to a PRTLightmap; every
 * problem is refused in one line starting with `name`: no extension, a size, UV set or kind out
 * of range, a layer that is missing, named twice, not FLOAT VEC3 of width × height texels, or not
 * finite.
 */
export async function readLightmap(gltf, name = 'lightmap.glb') {
  const json = gltf.parser.json;
  const d = json.extensions && json.extensions[kExtension];
  if (!d) fail(name, `holds no ${kExtension} (prt export BAKE --format lightmap -o NAME.glb writes one)`);
  if (d.kind !== 'lightmap' && d.kind !== 'lightmap-sh') fail(name, `${kExtension}: unknown kind '${d.kind}'`);
  const lm = d.lightmap || {};
  const side = (v) => Number.isInteger(v) && v >= 1 && v <= kMaxSide;
  if (!side(lm.width) || !side(lm.height)) fail(name, `${kExtension}: lightmap size ${lm.width} x ${lm.height} (1..${kMaxSide} each)`);
  if (!Number.isInteger(lm.texCoord) || lm.texCoord < 0 || lm.texCoord > 1) fail(name, `${kExtension}: texCoord ${lm.texCoord} (0 or 1)`);
  if (!Array.isArray(d.layers) || d.layers.length === 0) fail(name, `${kExtension}: no layers`);
  const texels = lm.width * lm.height, layers = new Map();
  for (const l of d.layers) {
    if (!l || typeof l.name !== 'string' || !l.name) fail(name, `${kExtension}: a layer without a name`);
    if (layers.has(l.name)) fail(name, `${kExtension}: layer '${l.name}' named twice`);
    if (!Number.isInteger(l.accessor) || !json.accessors || !json.accessors[l.accessor])
      fail(name, `${kExtension}: layer '${l.name}' names accessor ${l.accessor}, which the file lacks`);
    const a = json.accessors[l.accessor];
    if (a.type !== 'VEC3' || a.componentType !== 5126 || a.count !== texels)
      fail(name, `${kExtension}: layer '${l.name}' is ${a.count} ${a.type} of component type ${a.componentType}, ${texels} FLOAT VEC3 expected`);
    const values = (await gltf.parser.getDependency('accessor', l.accessor)).array;
    for (let i = 0; i < values.length; ++i)
      if (!Number.isFinite(values[i])) fail(name, `${kExtension}: layer '${l.name}' value ${i} is not finite`);
    layers.set(l.name, values);
  }
  if (d.kind === 'lightmap' && !layers.has('f')) fail(name, `${kExtension}: a plain lightmap without its layer 'f'`);
  return new PRTLightmap(d, layers, name);
}

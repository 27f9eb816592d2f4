// The GLTFLoader plugin for prtkit bakes (the PRTKIT_radiance_transfer extension,
// docs/extensions/PRTKIT_radiance_transfer; formats 1-4's extras.prtkit too):
//
//   const loader = new GLTFLoader().register((parser) => new PRTKitRadianceTransfer(parser, { renderer }));
//   const gltf = await loader.loadAsync('bunny.glb');
//   const prt = gltf.userData.prtkit;   // a PRTBake; its meshes already wear prtkit materials
//                                       // (a probe bake: a ProbeGridLighting; a Haar bake: a
//                                       // HaarLighting)
//
// An asset that is not a bake loads untouched (userData.prtkit stays undefined) unless
// options.required; a bake that cannot be shown rejects the load with one line naming the file.
import { bakeFormat, bands as kBands } from 'prt:constants';
import { bakeObject, checkParsedBake, readBake } from '../../src/bake.js';
import { glossyFromFile } from '../../src/glossy.js';
import { PRTBake } from './prt_bake.js';
import { ProbeGridLighting } from './probe_grid_lighting.js';
import { HaarLighting } from './haar_lighting.js';

export class PRTKitRadianceTransfer {
  /**
   * options: { name: the file's name in messages, renderer: a WebGLRenderer whose limits apply
   * (else WebGL2's guaranteed ones), required: reject an asset that is not a bake, texelPoints:
   * the texel points of per-texel glossy matrices and Haar rows (a Float32Array, what prt web
   * writes beside its bake: data.bake.texelPoints; such bakes are refused without them) }.
   */
  constructor(parser, options = {}) {
    this.parser = parser;
    this.name = bakeFormat.extension;
    this.options = options;
  }

  // Before GLTFLoader builds the scene: the document checked as prt checks it (bake.js,
  // checkParsedBake), so a malformed accessor or index is refused naming the file rather than
  // failing inside GLTFLoader with a bare JavaScript error.
  beforeRoot() {
    const o = this.options;
    if (bakeObject(this.parser.json)) checkParsedBake(this.parser, o.name || 'glTF asset');
    return null;
  }

  async afterRoot(result) {
    const o = this.options, name = o.name || 'glTF asset';
    if (!bakeObject(this.parser.json)) {
      if (o.required) throw new Error(`${name}: is a glTF file but not a prtkit bake (no ${bakeFormat.extension} extension)`);
      return;
    }
    const caps = o.renderer && o.renderer.capabilities;
    // uL[pad4(B²)] plus a few other uniforms must fit the vertex shader's uniform vectors
    // (WebGL2 guarantees 256: 15 bands).
    // (WebGL2 guarantees 256: 15 bands); per-texel transfer, relit per pixel, the fragment
    // shader's (224 guaranteed: 14 bands).
    const vectors = caps ? caps.maxVertexUniforms : 256, fragment = caps ? caps.maxFragmentUniforms : 224;
    const limits = { maxTextureSize: caps ? caps.maxTextureSize : 4096,
                     maxBands: Math.min(kBands.maxPackedLight, Math.floor(Math.sqrt(vectors - 16))),
                     maxFragmentBands: Math.min(kBands.maxPackedLight, Math.floor(Math.sqrt(fragment - 16))) };
    const bake = await readBake(result, name, limits, { texelPoints: o.texelPoints });
    // A probe grid (prt probes) lights what moves through it: a ProbeGridLighting.
    if (bake.probes) {
      result.userData.prtkit = new ProbeGridLighting(bake, result.scene);
      return;
    }
    // A Haar bake (prt bake --basis haar) is relit on the CPU: a HaarLighting.
    if (bake.haar) {
      result.userData.prtkit = new HaarLighting(bake, result.scene, limits);
      return;
    }
    for (const t of bake.transfers) if (t.matrix) t.material = glossyFromFile(t, name);
    result.userData.prtkit = new PRTBake(bake, result.scene, limits);
  }
}

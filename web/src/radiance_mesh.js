// A mesh drawn from radiance made on the CPU (shaders/stages/radiance.vert): its geometry gets a
// per-vertex `radiance` attribute, filled from tightly packed copies of its positions, normals
// and albedo (GLTFLoader may interleave them) — how a probe bake's scene and a ball moving
// through the grid are drawn, each vertex shaded through the relit probes (probe_relighter.js),
// in the page and in prtkit-three, each with its host's material.
import * as THREE from 'three';

/** Three floats a vertex of a three.js attribute, tightly packed. */
export function packed(a) {
  const out = new Float32Array(a.count * 3);
  for (let v = 0; v < a.count; ++v) out[3 * v] = a.getX(v), out[3 * v + 1] = a.getY(v), out[3 * v + 2] = a.getZ(v);
  return out;
}

/**
 * { mesh (a THREE.Mesh of `geometry` wearing `material`, or `mesh` dressed so), radiance (the
 * attribute), positions, normals, albedo (`albedo` if given, else the geometry's colour, else
 * null: white) }.
 */
export function radianceMesh(geometry, material, albedo = null, mesh = null) {
  const V = geometry.getAttribute('position').count;
  const radiance = new THREE.Float32BufferAttribute(new Float32Array(3 * V), 3);
  geometry.setAttribute('radiance', radiance);
  const colour = geometry.getAttribute('color');
  const m = mesh || new THREE.Mesh(geometry, material);
  m.material = material;
  m.frustumCulled = false;
  return { mesh: m, radiance, positions: packed(geometry.getAttribute('position')),
           normals: packed(geometry.getAttribute('normal')), albedo: albedo || (colour ? packed(colour) : null) };
}

/** Shades the mesh's vertices through the relighter's grid (at `positions`, else the mesh's
 *  own: a ball placed elsewhere) into its radiance. */
export function shadeRadianceMesh(m, relighter, positions = null) {
  relighter.shadeVertices(positions || m.positions, m.normals, m.albedo, m.radiance.array);
  m.radiance.needsUpdate = true;
}

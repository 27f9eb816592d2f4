// A bake's mesh as GLTFLoader left it: one three.js Mesh per glTF mesh (a part), each part's
// place in the file's vertex order (the rows of a per-vertex transfer start there), and the
// library's framing of the whole (render::meshFraming: the bounding box's centre, the radius to
// the farthest vertex). Every bake has one, whatever its domain (bake.js, probe_bake.js).
import * as THREE from 'three';

function fail(name, what) {
  throw new Error(`${name}: ${what}`);
}

/**
 * The parts of the bake `prt` (its object in the glTF) in `gltf` (GLTFLoader's result):
 * { parts: [{ mesh, geometry, name, first, vertices, hasAlbedo }], vertices, triangles, centre
 * (THREE.Vector3), radius }. Throws one line naming the file when a part is not where the bake
 * says.
 */
export function meshParts(gltf, prt, name) {
  const json = gltf.parser.json;
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
    parts.push({ mesh: m, geometry: g, name: m.name, first, vertices: V, hasAlbedo: !!g.getAttribute('color') });
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
  return { parts, vertices, triangles, centre, radius: Math.max(Math.sqrt(r2), 1e-6) };
}

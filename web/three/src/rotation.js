// Rotations for the module: three.js's objects as the row-major 3 × 3 arrays the SH rotation
// takes (web/src/sh.js), and a light turned by one.
import * as THREE from 'three';
import { rotateLight as rotateCoefficients } from '../../src/sh.js';

const m4 = new THREE.Matrix4();

/** Row-major [[..], [..], [..]] of a THREE.Quaternion, Euler, Matrix3 or Matrix4 (its
 *  rotation part, scale removed). */
export function rotationRows(r) {
  if (r.isQuaternion) m4.makeRotationFromQuaternion(r);
  else if (r.isEuler) m4.makeRotationFromEuler(r);
  else if (r.isMatrix3) m4.setFromMatrix3(r);
  else if (r.isMatrix4) m4.extractRotation(r);
  else throw new Error('a rotation is a THREE.Quaternion, Euler, Matrix3 or Matrix4');
  const e = m4.elements;  // column-major
  return [[e[0], e[4], e[8]], [e[1], e[5], e[9]], [e[2], e[6], e[10]]];
}

/** The light turned by `rotation` (L'(ω) = L(Rᵀω), as prt render --rotate turns it): a new
 *  { bands, coeffs }. `prt render --rotate X,Y,Z` is new THREE.Euler(X, Y, Z, 'ZYX') in
 *  radians (X first, then Y, then Z). */
export function rotateLight(light, rotation) {
  return { bands: light.bands, coeffs: rotateCoefficients(light.bands, rotationRows(rotation), light.coeffs) };
}

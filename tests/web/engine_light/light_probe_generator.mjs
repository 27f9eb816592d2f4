// three.js's own LightProbeGenerator.fromCubeTexture on six faces given as raw RGBA bytes, under
// node: the only stand-in is a canvas whose getImageData hands back those bytes (three reads a
// face's pixels through a 2D canvas, nothing else of the DOM). Prints the probe's 27 floats.
//
//   node light_probe_generator.mjs FACES.bin N      (FACES.bin: six N×N RGBA faces, three's
//                                                    order px nx py ny pz nz, rows top first)
import fs from 'node:fs';

const [file, sizeText] = process.argv.slice(2);
const n = Number(sizeText);
const bytes = fs.readFileSync(file);
if (bytes.length !== 6 * n * n * 4) throw new Error(`${file}: expected six ${n}x${n} RGBA faces`);

const three = new URL('../../../web/node_modules/three/', import.meta.url);
const { LinearSRGBColorSpace } = await import(new URL('build/three.module.js', three));
const { LightProbeGenerator } = await import(
  new URL('examples/jsm/lights/LightProbeGenerator.js', three));

globalThis.document = {
  createElement: () => {
    let drawn = null;
    return {
      getContext: () => ({
        drawImage(image) { drawn = image; },
        getImageData: () => ({ data: drawn.data, width: drawn.width, height: drawn.height }),
      }),
    };
  },
};
const faces = [];
for (let f = 0; f < 6; ++f) {
  const data = new Uint8ClampedArray(bytes.buffer, bytes.byteOffset + f * n * n * 4, n * n * 4);
  faces.push({ width: n, height: n, data });
}
const probe = LightProbeGenerator.fromCubeTexture({ image: faces, colorSpace: LinearSRGBColorSpace });
console.log(JSON.stringify(probe.sh.toArray()));

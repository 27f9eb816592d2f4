// Data images: a count of RGBA32F texels laid out as a W × H 2D texture, texel t at
// (t mod W, t div W) — what the page's host interface reads (shaders/hosts/webgl2.glsl,
// prtTexel) where the desktop viewer has texture buffers.

/** W: 4096, or the GPU's maximum texture size if smaller. */
export function textureWidth(limits) {
  return Math.min(limits.maxTextureSize, 4096);
}

/** `texels` texels as a zeroed { width, height, data } image; throws one line naming `what`
 *  when it needs more rows than the GPU's maximum texture size. */
export function textureShape(texels, limits, name, what, advice = '') {
  const W = textureWidth(limits);
  const H = Math.max(1, Math.ceil(texels / W));
  if (H > limits.maxTextureSize)
    throw new Error(`${name}: ${what} needs ${texels} texels, more than the ${W} × ${limits.maxTextureSize} textures of this WebGL hold${advice}`);
  return { width: W, height: H, data: new Float32Array(W * H * 4) };
}

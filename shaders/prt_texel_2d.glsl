// Data textures as WebGL2 has them (the page's and the three.js module's hosts): an RGBA32F 2D
// texture, texel t at (t mod width, t div width) — web/src/texels.js lays them out.
precision highp sampler2D;
#define PRT_TEXELS highp sampler2D
vec4 prtTexel(highp sampler2D s, int t) {
  int w = textureSize(s, 0).x;
  return texelFetch(s, ivec2(t % w, t / w), 0);
}

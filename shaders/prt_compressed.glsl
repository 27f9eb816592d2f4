// prtkit relighting from CPCA-compressed transfer (Sloan, Hall, Hart & Snyder 2003, §5), shared
// by the desktop viewer (GLSL 3.30) and the web page (GLSL ES 3.00). Layouts: include/prt/
// relight/shader_transfer.hpp. The host declares, before this file:
//   vec4 prtWeightTexel(int t)   per-vertex texels, T per vertex: slot 0 the cluster id k (a
//                                float), slot 1 + j the weight w_j (j < N), zero padding
//   vec4 prtClusterTexel(int t)  this frame's cluster projections, (r, g, b, -) per value:
//                                texel (k(N + 1) + j)·Q + i, j = 0 the mean, j > 0 basis j − 1
// Value i of the vertex starting at texel `base` (Q values per cluster vector):
//   x_i = P(k, 0, i) + Σ_{j<N} w_j P(k, j + 1, i)
// vectors (Q = 1): x_0 = c_k + Σ_j w_j d_kj = T̂(v)·L'; matrices (Q = B²): x_i = (M̂_v L')_i.
int prtCompressedRow(int base, int basisCount) {
  return int(prtWeightTexel(base).x + 0.5) * (basisCount + 1);
}
vec3 prtCompressedValue(int base, int row, int basisCount, int coeffs, int i) {
  vec3 x = prtClusterTexel(row * coeffs + i).rgb;
  vec4 w = prtWeightTexel(base);
  for (int s = 1; s <= basisCount; ++s) {
    if ((s & 3) == 0) w = prtWeightTexel(base + (s >> 2));
    x += w[s & 3] * prtClusterTexel((row + s) * coeffs + i).rgb;
  }
  return x;
}
// Exit radiance before albedo of compressed vector transfer: c_k + Σ_j w_j d_kj.
vec3 prtRelightCompressed(int base, int basisCount) {
  return prtCompressedValue(base, prtCompressedRow(base, basisCount), basisCount, 1, 0);
}

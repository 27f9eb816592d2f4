#include "prt/relight/cluster_table.hpp"

#include <string>

#include "prt/core/error.hpp"

namespace prt::relight {

CompressedVertexTexels packCompressedVertices(const CompressedTransfer& t) {
  // Float32 holds every integer up to 2^24 exactly; a shader reads the id as a float.
  if (t.clusters < 1 || t.clusters > (1 << 24))
    throw Error("relight: " + std::to_string(t.clusters) +
                " clusters: a shader reads cluster ids as floats, exact below 2^24");
  const std::size_t nv = t.vertexCount, N = static_cast<std::size_t>(t.basisCount);
  if (t.basisCount < 0 || t.cluster.size() != nv || t.weights.size() != nv * N)
    throw Error("relight: compressed transfer arrays do not match its shape");
  CompressedVertexTexels out;
  out.basisCount = t.basisCount;
  out.texelsPerVertex = compressedTexelsPerVertex(t.basisCount);
  const std::size_t slots = 4 * static_cast<std::size_t>(out.texelsPerVertex);
  out.rgba.assign(nv * slots, 0.0f);
  for (std::size_t v = 0; v < nv; ++v) {
    float* dst = out.rgba.data() + v * slots;
    dst[0] = static_cast<float>(t.cluster[v]);
    for (std::size_t j = 0; j < N; ++j) dst[1 + j] = t.weights[v * N + j];
  }
  return out;
}

void packClusterTable(const ClusterLight& p, std::vector<float>& rgba) {
  const std::size_t values = p.rgb.size() / 3;
  rgba.resize(4 * values);
  for (std::size_t q = 0; q < values; ++q) {
    rgba[4 * q] = p.rgb[3 * q];
    rgba[4 * q + 1] = p.rgb[3 * q + 1];
    rgba[4 * q + 2] = p.rgb[3 * q + 2];
    rgba[4 * q + 3] = 0.0f;
  }
}

void evalPackedVertex(const CompressedVertexTexels& vt, const std::vector<float>& table, int coeffs,
                      std::size_t v, Rgb* out) {
  const std::size_t Q = static_cast<std::size_t>(coeffs),
                    N = static_cast<std::size_t>(vt.basisCount);
  const float* slot = vt.rgba.data() + v * 4 * static_cast<std::size_t>(vt.texelsPerVertex);
  const std::size_t k = static_cast<std::size_t>(slot[0]);
  // Texel (k(N+1) + j)·Q + i, its (r, g, b) at 4 times that.
  const float* row = table.data() + 4 * k * (N + 1) * Q;
  for (std::size_t i = 0; i < Q; ++i) {
    Rgb e(row[4 * i], row[4 * i + 1], row[4 * i + 2]);
    for (std::size_t j = 0; j < N; ++j) {
      const float* d = row + 4 * ((j + 1) * Q + i);
      e += slot[1 + j] * Rgb(d[0], d[1], d[2]);
    }
    out[i] = e;
  }
}

}  // namespace prt::relight

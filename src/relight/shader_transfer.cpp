#include "prt/relight/shader_transfer.hpp"

#include <string>

#include "prt/core/error.hpp"
#include "prt/geometry/texel_samples.hpp"

namespace prt::relight {

const char* toString(ShaderPath path) {
  switch (path) {
    case ShaderPath::DenseVector:
      return "dense vectors";
    case ShaderPath::DenseMatrix:
      return "dense matrices in the vertex shader";
    case ShaderPath::CpcaVector:
      return "CPCA-compressed vectors";
    case ShaderPath::CpcaMatrix:
      return "CPCA-compressed matrices";
    case ShaderPath::CpuRadiance:
      return "matrices relit on the CPU";
  }
  return "?";
}

namespace {

void checkPath(const Transfer& t, ShaderPath path) {
  const std::string what = std::string("the ") + toString(t.layout()) + " transfer";
  if (t.domain() == TransferDomain::Texels && t.isMatrix() && path != ShaderPath::CpcaMatrix)
    throw Error(kPerTexelMatricesRefusal);
  switch (path) {
    case ShaderPath::DenseVector:
    case ShaderPath::CpcaVector:
      if (t.bands() > bands::kMaxPackedLight)
        throw Error(
            bands::bandLimitMessage(what, t.bands(), "the viewers' light", bands::kMaxPackedLight));
      break;
    case ShaderPath::DenseMatrix:
      if (t.channels() != 1)
        throw Error(
            "the vertex-shader glossy path takes scalar matrices only (relight them on "
            "the CPU: --glossy-on cpu)");
      [[fallthrough]];
    case ShaderPath::CpcaMatrix:
      if (t.bands() > bands::kMaxShaderGlossy)
        throw Error(bands::bandLimitMessage(what, t.bands(), "the shaders' glossy response",
                                            bands::kMaxShaderGlossy) +
                    " (relight them on the CPU: --glossy-on cpu)");
      break;
    case ShaderPath::CpuRadiance:
      break;
  }
  if (t.compressed() && t.cpca().clusters > kMaxShaderClusters)
    throw Error(std::to_string(t.cpca().clusters) +
                " clusters: a shader reads cluster ids as floats, exact below 2^24");
}

}  // namespace

bool drawnPerPixel(const Transfer& t) { return t.domain() == TransferDomain::Texels; }

ShaderPath shaderPath(const Transfer& t, bool matricesOnGpu) {
  ShaderPath path;
  if (!t.isMatrix())
    path = t.compressed() ? ShaderPath::CpcaVector : ShaderPath::DenseVector;
  else if (t.domain() == TransferDomain::Texels)
    path = t.compressed() ? ShaderPath::CpcaMatrix : ShaderPath::DenseMatrix;  // (refused)
  else if (!matricesOnGpu)
    path = ShaderPath::CpuRadiance;
  else
    path = t.compressed() ? ShaderPath::CpcaMatrix : ShaderPath::DenseMatrix;
  checkPath(t, path);
  return path;
}

int shaderTexelsPerRow(const Transfer& t, ShaderPath path) {
  const int n = t.coeffs();
  switch (path) {
    case ShaderPath::DenseVector:
      return t.channels() == 1 ? paddedCoeffs(t.bands()) / 4 : n;
    case ShaderPath::DenseMatrix:
      return n * ((n + 3) / 4);
    case ShaderPath::CpcaVector:
    case ShaderPath::CpcaMatrix:
      return (t.cpca().basisCount + 1 + 3) / 4;
    case ShaderPath::CpuRadiance:
      return 0;
  }
  return 0;
}

ShaderRows packShaderRows(const Transfer& t, ShaderPath path) {
  checkPath(t, path);
  ShaderRows out;
  out.path = path;
  out.texelsPerRow = shaderTexelsPerRow(t, path);
  out.channels = t.channels();
  out.perPixel = drawnPerPixel(t);
  if (out.perPixel) out.lightmap = t.shape().lightmap;
  const std::size_t rows = t.rowCount(), slots = 4 * static_cast<std::size_t>(out.texelsPerRow);
  out.rgba.assign(rows * slots, 0.0f);
  const std::size_t n = static_cast<std::size_t>(t.coeffs());
  switch (path) {
    case ShaderPath::DenseVector:
      PRT_CHECK(!t.compressed() && !t.isMatrix(), "dense vector path of another transfer");
      for (std::size_t r = 0; r < rows; ++r) {
        const float* src = t.row(r);
        float* dst = out.rgba.data() + r * slots;
        if (t.channels() == 1)
          std::copy(src, src + n, dst);
        else
          for (std::size_t i = 0; i < n; ++i) std::copy(src + 3 * i, src + 3 * i + 3, dst + 4 * i);
      }
      break;
    case ShaderPath::DenseMatrix: {
      PRT_CHECK(!t.compressed() && t.isMatrix(), "dense matrix path of another transfer");
      // Row i of vertex r at texels r·T + i·⌈n/4⌉, its n entries zero-padded.
      const std::size_t rowTexels = (n + 3) / 4;
      for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t i = 0; i < n; ++i) {
          const float* src = t.row(r) + i * n;
          std::copy(src, src + n, out.rgba.data() + r * slots + i * rowTexels * 4);
        }
      break;
    }
    case ShaderPath::CpcaVector:
    case ShaderPath::CpcaMatrix: {
      const CpcaRows& c = t.cpca();
      const std::size_t N = static_cast<std::size_t>(c.basisCount);
      for (std::size_t r = 0; r < rows; ++r) {
        float* dst = out.rgba.data() + r * slots;
        dst[0] = static_cast<float>(c.cluster[r]);
        for (std::size_t j = 0; j < N; ++j) dst[1 + j] = c.weights[r * N + j];
      }
      out.basisCount = c.basisCount;
      break;
    }
    case ShaderPath::CpuRadiance:
      break;
  }
  return out;
}

std::size_t clusterTableTexels(const Transfer& t) {
  const CpcaRows& c = t.cpca();
  return static_cast<std::size_t>(c.clusters) * static_cast<std::size_t>(c.basisCount + 1) *
         (t.isMatrix() ? static_cast<std::size_t>(t.coeffs()) : 1);
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

void evalPackedRow(const ShaderRows& rows, const std::vector<float>& table, int coeffs,
                   std::size_t r, Rgb* out) {
  const std::size_t Q = static_cast<std::size_t>(coeffs),
                    N = static_cast<std::size_t>(rows.basisCount);
  const float* slot = rows.rgba.data() + r * 4 * static_cast<std::size_t>(rows.texelsPerRow);
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

ShaderRows packRadianceLightmap(std::span<const Rgb> radiance,
                                const TransferShape::LightmapSize& lightmap, const Rgb& lightDc) {
  if (radiance.size() != lightmap.texels())
    throw Error(std::to_string(radiance.size()) + " radiance values for a " +
                std::to_string(lightmap.width) + " x " + std::to_string(lightmap.height) +
                " lightmap");
  ShaderRows out;
  out.path = ShaderPath::DenseVector;
  out.texelsPerRow = 1;  // RGB at one band: one (r, g, b, 0) texel
  out.channels = 3;
  out.perPixel = true;
  out.lightmap = lightmap;
  const auto inverse = [](float l) { return l != 0.0f ? 1.0f / l : 0.0f; };
  const Rgb scale(inverse(lightDc.x), inverse(lightDc.y), inverse(lightDc.z));
  out.rgba.assign(4 * radiance.size(), 0.0f);
  for (std::size_t r = 0; r < radiance.size(); ++r) {
    const Rgb t = radiance[r] * scale;
    float* dst = out.rgba.data() + 4 * r;
    dst[0] = t.x, dst[1] = t.y, dst[2] = t.z;
  }
  return out;
}

TransferShape radianceLightmapShape(const TransferShape::LightmapSize& lightmap) {
  TransferShape shape;
  shape.domain = TransferDomain::Texels;
  shape.bands = 1;
  shape.channels = 3;
  shape.rows = {0, lightmap.texels()};
  shape.lightmap = lightmap;
  return shape;
}

Rgb evalPerPixel(const ShaderRows& rows, std::span<const float> light, int bands,
                 const std::vector<float>& table, Vec2f uv) {
  PRT_CHECK(rows.perPixel, "evalPerPixel of per-vertex rows");
  const TexelTaps taps = bilinearTaps(uv, rows.lightmap.width, rows.lightmap.height);
  const std::size_t slots = 4 * static_cast<std::size_t>(rows.texelsPerRow);
  Rgb r(0.0f);
  for (int k = 0; k < 4; ++k) {
    Rgb e(0.0f);
    if (rows.path == ShaderPath::CpcaVector) {
      evalPackedRow(rows, table, 1, taps.texel[k], &e);
    } else {
      PRT_CHECK(rows.path == ShaderPath::DenseVector, "evalPerPixel: vector paths only");
      // prt_relight.glsl: scalar rows four coefficients a texel, RGB rows one texel (r, g, b, 0)
      // per coefficient, against the packed light (r, g, b, 0) per coefficient.
      const float* row = rows.rgba.data() + taps.texel[k] * slots;
      for (int i = 0; i < bands * bands; ++i) {
        const float* l = light.data() + 4 * i;
        e += rows.channels == 3
                 ? Rgb(row[4 * i] * l[0], row[4 * i + 1] * l[1], row[4 * i + 2] * l[2])
                 : row[i] * Rgb(l[0], l[1], l[2]);
      }
    }
    r += e * taps.weight[k];
  }
  return r;
}

std::array<float, 64> shaderKernel(std::span<const float> perCoefficient) {
  std::array<float, 64> out{};
  for (int l = 0; l < bands::kMaxShaderGlossy; ++l)
    for (int m = -l; m <= l; ++m) {
      const int i = sh::index(l, m);
      if (std::size_t(i) < perCoefficient.size())
        out[i] = float(perCoefficient[i] * sh::normalization(l, m));
    }
  return out;
}

}  // namespace prt::relight

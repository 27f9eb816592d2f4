// relight()'s one dispatch over layout × representation (relight.hpp), the light's preparation
// and the checks every kernel relies on.

#include "prt/relight/relight.hpp"

#include <algorithm>
#include <string>

#include "kernels.hpp"
#include "prt/core/error.hpp"

namespace prt::relight {

std::string RelightInfo::warning() const {
  if (!transferTruncated) return "";
  return "the light has " + std::to_string(lightBands) + " bands but the transfer has " +
         std::to_string(transferBands) + "; relighting with " + std::to_string(bands) +
         " bands (the transfer's upper bands see no light)";
}

PreparedLight prepareLight(const sh::RgbSh& light, int transferBands, const sh::Rotation* rotation,
                           RelightInfo* info) {
  sh::checkBands(light.bands);
  sh::checkBands(transferBands);
  PRT_CHECK(light.c.size() == static_cast<std::size_t>(light.bands * light.bands),
            "light coefficient count does not match its bands");
  const int bands = std::min(light.bands, transferBands);
  const int n = bands * bands;
  if (info) {
    info->bands = bands;
    info->lightBands = light.bands;
    info->transferBands = transferBands;
    info->lightTruncated = light.bands > transferBands;
    info->transferTruncated = light.bands < transferBands;
  }
  // Rotation is block-diagonal over bands, so cutting then rotating equals rotating then cutting.
  std::vector<Rgb> coeffs(light.c.begin(), light.c.begin() + n);
  if (rotation) {
    if (rotation->bands() < bands)
      throw Error("relight: the rotation was built for " + std::to_string(rotation->bands()) +
                  " bands but " + std::to_string(bands) + " are needed");
    std::vector<Rgb> rotated(n);
    if (rotation->bands() == bands) {
      rotation->apply(coeffs.data(), rotated.data());
    } else {  // a rotation built for more bands: pad with zeros, rotate, cut
      const int m = rotation->bands() * rotation->bands();
      std::vector<Rgb> padded(m, Rgb(0.0f)), out(m);
      std::copy(coeffs.begin(), coeffs.end(), padded.begin());
      rotation->apply(padded.data(), out.data());
      std::copy_n(out.begin(), n, rotated.begin());
    }
    coeffs.swap(rotated);
  }
  return prepareLight(coeffs, bands);
}

PreparedLight prepareLight(std::span<const Rgb> coeffs, int bands) {
  const int n = bands * bands;
  PRT_CHECK(coeffs.size() >= static_cast<std::size_t>(n), "fewer rotated coefficients than bands");
  PreparedLight p;
  p.bands = bands;
  const int pad = (n + 3) & ~3;
  // Scalar layouts, one after the other: three planes, then each value splatted four times.
  p.planar.assign(static_cast<std::size_t>(pad) * 3 + static_cast<std::size_t>(n) * 12, 0.0f);
  float* splat = p.planar.data() + 3 * pad;
  p.interleaved.resize(static_cast<std::size_t>(n) * 3);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      p.planar[c * pad + i] = coeffs[i][c];
      for (int k = 0; k < 4; ++k) splat[12 * i + 4 * c + k] = coeffs[i][c];
      p.interleaved[3 * i + c] = coeffs[i][c];
    }
  }
  return p;
}

namespace {

/// The checks every kernel relies on: the light's bands, the output, the albedo and, for
/// view-dependent layouts, one position and normal per row and the material's bands.
Albedo checkInputs(const Transfer& t, const PreparedLight& light, const PreparedMaterial& material,
                   const Surface& surface, std::span<Rgb> out) {
  requireShTransfer(t);
  const std::size_t rows = t.rowCount();
  if (t.channels() != 1 && t.channels() != 3)
    throw Error("relight: the transfer has " + std::to_string(t.channels()) +
                " channels (expected 1 or 3)");
  if (light.bands < 1 || light.bands > t.bands())
    throw Error("relight: the prepared light has " + std::to_string(light.bands) +
                " bands, the transfer " + std::to_string(t.bands()));
  if (out.size() != rows)
    throw Error("relight: the output holds " + std::to_string(out.size()) + " values for " +
                std::to_string(rows) + " rows");
  if (t.isMatrix()) {
    if (material.bands != t.bands())
      throw Error("relight: the material is prepared for " + std::to_string(material.bands) +
                  " bands, the transfer has " + std::to_string(t.bands()));
    if (surface.positions.size() != rows || surface.normals.size() != rows)
      throw Error("relight: glossy transfer needs one position and normal per row (" +
                  std::to_string(rows) + ")");
  }
  return Albedo(surface.albedo, rows);
}

}  // namespace

void relightPrepared(const Transfer& t, const PreparedLight& light,
                     const PreparedMaterial& material, const Surface& surface, const Vec3f& eye,
                     std::span<Rgb> out) {
  const Albedo albedo = checkInputs(t, light, material, surface, out);
  // Vectors are diffuse: the material's kd, when it sets one, replaces the albedo.
  const Rgb kd = material.kd ? *material.kd : Rgb(1.0f);
  const Albedo diffuse = material.kd ? Albedo(std::span<const Rgb>(&kd, 1), t.rowCount()) : albedo;
  switch (t.representation()) {
    case Transfer::Representation::Dense:
      if (t.isMatrix())
        detail::relightDenseMatrices(t, light, material, surface, eye, albedo, out);
      else
        detail::relightDenseVectors(t, light, diffuse, out);
      return;
    case Transfer::Representation::Cpca:
      if (t.isMatrix())
        detail::relightCpcaMatrices(t, light, material, surface, eye, albedo, out);
      else
        detail::relightCpcaVectors(t, projectClusters(t, light), diffuse, out);
      return;
  }
}

void requireShTransfer(const Transfer& t) {
  if (t.isHaar())
    throw Error("relight: the transfer is Haar wavelets (" + t.shape().describe() +
                "); it is relit under a Haar light (relight::relightHaar), not SH coefficients");
}

RelightInfo relight(const Transfer& t, const sh::RgbSh& light, const Material& material,
                    const Surface& surface, const Vec3f& eye, std::span<Rgb> out,
                    const Mat3d& rotation) {
  requireShTransfer(t);
  RelightInfo info;
  const int bands = std::min(light.bands, t.bands());
  PreparedLight p;
  if (rotation == Mat3d::identity()) {
    p = prepareLight(light, t.bands(), nullptr, &info);
  } else {
    const sh::Rotation rot(bands, rotation);
    p = prepareLight(light, t.bands(), &rot, &info);
  }
  // The material's kernels are only read for matrices; vectors need its kd alone.
  PreparedMaterial pm;
  if (t.isMatrix())
    pm = prepareMaterial(material, t.bands());
  else
    pm.kd = material.diffuse;
  relightPrepared(t, p, pm, surface, eye, out);
  return info;
}

std::vector<Rgb> relight(const Transfer& t, const sh::RgbSh& light, const Material& material,
                         const Surface& surface, const Vec3f& eye, const Mat3d& rotation,
                         RelightInfo* info) {
  std::vector<Rgb> out(t.rowCount());
  const RelightInfo i = relight(t, light, material, surface, eye, out, rotation);
  if (info) *info = i;
  return out;
}

}  // namespace prt::relight

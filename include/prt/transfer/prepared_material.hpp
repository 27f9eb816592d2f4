#pragma once
// A material's SH kernels at one band count, and the two response vectors they give at a
// surface point (material.hpp has the maths):
//
//   d_i = (A_l/π) Y_i(n)      the clamped cosine about the normal (the diffuse part)
//   g_i = Λ_l Y_i(R)          the lobe about the view reflected in the normal (the glossy part)
//
// so that the light leaving the point toward the eye is kd (d·L') + ks (g·L') for the light L'
// arriving there. Used where that exit radiance is needed: relighting glossy transfer
// (relight/relight.hpp and its kernels) and the matrix bake, whose bounces carry the
// light a glossy surface sends toward another vertex (transport/bake.hpp).

#include <optional>
#include <span>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/transfer/albedo.hpp"
#include "prt/transfer/material.hpp"

namespace prt {

struct PreparedMaterial {
  int bands = 0;
  std::vector<float> diffuse;  ///< A_l/π per coefficient i (expanded from bands)
  std::vector<float> glossy;   ///< Λ_l per coefficient i; empty when the material has no lobe
  Rgb specular{0.0f};          ///< ks
  std::optional<Rgb> kd;       ///< material.diffuse

  /// The two per-vertex response vectors of B² floats: d_i = (A_l/π) Y_i(n) into `d` and, for
  /// a glossy material, g_i = Λ_l Y_i(R) with R the view toward `eye` reflected about n, into
  /// `g` (untouched otherwise). `scratch` holds B² floats.
  void responses(const Vec3f& position, const Vec3f& normal, const Vec3f& eye, float* d, float* g,
                 float* scratch) const;
  /// kd at row r: the material's, else the albedo's (albedo.hpp).
  Rgb diffuseAt(const Albedo& albedo, std::size_t r) const { return kd ? *kd : albedo.at(r); }
};
/// The kernels of `material` at `bands` (1..sh::kMaxBands; throws prt::Error otherwise).
PreparedMaterial prepareMaterial(const Material& material, int bands);

}  // namespace prt

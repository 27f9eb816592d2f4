#pragma once
// Transfer data: per vertex, the SH vector that maps lighting to exit radiance.
//   T_i(p) = (1/π) ∫ Y_i(ω) V(p,ω) max(n·ω, 0) dω   (+ inter-reflected light)
//   R(p) = albedo(p) ⊙ Σ_i T_i(p) L_i
// (Sloan, Kautz & Snyder, "Precomputed Radiance Transfer for Real-Time Rendering in Dynamic,
// Low-Frequency Lighting Environments", SIGGRAPH 2002.)
// Scalar transfer (uniform albedo) holds one float per coefficient; RGB transfer (coloured
// inter-reflection) holds three, channel-interleaved: data[(v*B² + i)*3 + c].
// For an RGB transfer the albedo is already folded into the bounces but not the final
// albedo(p) factor, which is applied at relighting for both kinds.

#include <cstdint>
#include <string>
#include <vector>

namespace prt {

enum class TransferMode { Unshadowed, Shadowed, Interreflected };
const char* toString(TransferMode mode);
/// Parses "unshadowed" | "shadowed" | "interreflected"; throws prt::Error otherwise.
TransferMode parseTransferMode(const std::string& s);

struct TransferField {
  int bands = 0;
  int channels = 1;  ///< 1 (scalar) or 3 (RGB)
  std::size_t vertexCount = 0;
  std::vector<float> data;  ///< vertexCount × B² × channels

  int coeffs() const { return bands * bands; }
  std::size_t stride() const { return static_cast<std::size_t>(coeffs()) * channels; }
  float* vertex(std::size_t v) { return data.data() + v * stride(); }
  const float* vertex(std::size_t v) const { return data.data() + v * stride(); }
  /// The first b bands of every vertex (a b-band bake equals the first b² coefficients).
  TransferField truncated(int b) const;
};

}  // namespace prt

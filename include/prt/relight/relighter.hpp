#pragma once
// A relighting frame loop (prt render --turntable, prt view's CPU path, an application's render
// loop): one transfer and surface, a material, and per frame a rotated light and an eye. Each
// frame goes through relight()'s one dispatch; the relighter keeps what frames share:
//
//   * the transfer cut to the band count shown (Transfer::cut, made once per change — the one
//     answer for both representations);
//   * the material's kernels at that band count;
//   * for dense matrices, when only the light changed since the last frame (it turns under a
//     still camera), the matrices collapsed for that eye (view_transfer.hpp), built on the
//     second such frame: every further light-only frame is a vector relighting (23× less work
//     than the matrices at 5 bands, docs/performance.md);
//   * the last radiance: a frame with the same light, eye, bands and material returns it as is.

#include <span>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/relight/relight.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::relight {

class Relighter {
 public:
  Relighter() = default;
  /// The transfer to relight (any layout and representation) and where its rows are (the
  /// surface's spans must outlive the relighter). Starts at the transfer's bands with the
  /// default (white Lambert) material.
  Relighter(Transfer transfer, Surface surface);

  const Transfer& transfer() const { return full_; }
  /// The transfer at the current band count (what is relit).
  const Transfer& shown() const { return cut_; }

  void setMaterial(const Material& material);
  const Material& material() const { return material_; }
  /// 1..transfer().bands() (throws prt::Error otherwise).
  void setBands(int bands);
  int bands() const { return cut_.bands(); }

  /// Exit radiance per row under `light` rotated by `rotation`, seen from `eye` (matrices).
  std::span<const Rgb> relight(const sh::RgbSh& light, const Mat3d& rotation, const Vec3f& eye,
                               RelightInfo* info = nullptr);
  /// The same for a light already rotated: (r, g, b) per coefficient, lightBands² of them (a
  /// viewer's packed light); the light is cut to bands() when it has more.
  std::span<const Rgb> relightRotated(std::span<const Rgb> rotated, int lightBands,
                                      const Vec3f& eye, RelightInfo* info = nullptr);

  /// The last frame's radiance.
  std::span<const Rgb> radiance() const { return radiance_; }
  /// Frames relit (not served from the last radiance) so far.
  int frames() const { return frames_; }
  /// Of those, the ones relit from the view-collapsed transfer (only the light had changed).
  int lightOnlyFrames() const { return lightOnlyFrames_; }

 private:
  Transfer full_, cut_;
  Surface surface_;
  Material material_;
  PreparedMaterial prepared_;
  std::vector<Rgb> radiance_;
  // What the last frame was made from.
  bool haveLast_ = false;
  bool viewChanged_ = true;  ///< bands or material changed since the last frame
  Vec3f lastEye_{0.0f};
  std::vector<Rgb> lastLight_;
  int lastLightBands_ = 0;
  Transfer collapsed_;  ///< viewTransfer for lastEye_, when valid
  bool collapsedValid_ = false;
  int frames_ = 0, lightOnlyFrames_ = 0;
};

}  // namespace prt::relight

#pragma once
// A bake as a picture shows it, on the CPU: its transfer over the mesh with a material, relit
// under an SH light rotated at will and seen from an eye, and how each pixel is shaded from the
// rows — the one dispatch point for the domain and the base-colour texture that prt render,
// auto exposure (relitSurvey: the viewers' and the page's first exposure) and the bake
// fuzzer draw through:
//
//   per vertex   rows relit at the vertices, blended with the hit's barycentrics
//                (vertexRadianceShader);
//   per texel    rows relit as texelRelight says (vectors white with the albedo per pixel,
//                matrices at the texels' sample points), fetched bilinearly at the hit's
//                lightmap UV (texelRadianceShader);
//   textured     the base-colour texture multiplies the diffuse part per pixel, a glossy
//                matrix lobe relit apart and added untextured (render/base_colour.hpp);
//   encoded      (matrices, diffuse materials) the rows' diffuse radiance through an engine's
//                irradiance encoding instead of PRT's (relight/encoded_diffuse.hpp), drawn the
//                same way.

#include <optional>
#include <span>
#include <vector>

#include "prt/geometry/mesh.hpp"
#include "prt/image/color.hpp"
#include "prt/raytrace/occluder.hpp"
#include "prt/relight/relighter.hpp"
#include "prt/render/camera.hpp"
#include "prt/render/render.hpp"
#include "prt/render/texel_points.hpp"
#include "prt/sh/irradiance_encoding.hpp"
#include "prt/sh/sh.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/transfer.hpp"

namespace prt::render {

class RelitView {
 public:
  /// `mesh`, `occluder` (built from it) and `transfer` (complete, over the mesh's vertices or
  /// its lightmap) must outlive the view.
  RelitView(const Mesh& mesh, const Occluder& occluder, const Transfer& transfer,
            const Material& material);
  /// A view with no occluder, for a rasteriser that only needs the rows relit (the desktop
  /// viewer's CPU path): per-vertex transfer only (throws prt::Error for per-texel), and no
  /// shader().
  RelitView(const Mesh& mesh, const Transfer& transfer, const Material& material);

  /// Cuts the transfer to `bands` (1..its bands) for the relights that follow.
  void setBands(int bands);
  int bands() const { return relighter_.bands(); }
  const Material& material() const { return material_; }
  /// Relights with another material from the next relight on (per vertex: per texel the rows'
  /// sample points were placed for the first).
  void setMaterial(const Material& material);
  /// Relights through `encoding` from the next relight on (none: PRT's own radiance): each
  /// row's diffuse radiance from the encoded irradiance of the light arriving there
  /// (relight::encodedDiffuse). Throws prt::Error for vector transfer or a glossy material
  /// (an encoding holds irradiance: diffuse shading only).
  void setEncoding(std::optional<sh::IrradianceEncoding> encoding);
  std::optional<sh::IrradianceEncoding> encoding() const { return encoding_; }
  /// "vertex" or "texel": what a row is, for messages.
  const char* rowNoun() const;
  /// True when the rows are the mesh's vertices (other radiance can be drawn: shader(rows)).
  bool perVertex() const { return transfer_.domain() == TransferDomain::Vertices; }

  /// Relights every row under `light` rotated by `rotation`, seen from `eye` (matrices): the
  /// rows' radiance (the part the texture multiplies, when the mesh is textured). Throws
  /// prt::Error naming `name` when a row's radiance is not finite.
  std::span<const Rgb> relight(const sh::RgbSh& light, const Mat3d& rotation, const Vec3f& eye,
                               const std::string& name, relight::RelightInfo* info = nullptr);
  /// The same for a light already rotated (a viewer's packed light: (r, g, b) per coefficient,
  /// lightBands² of them). Returns false when nothing changed since the last relight (the same
  /// light, eye, bands and material): radiance() and highlight() then still hold it. Not with
  /// an encoding (PRT_CHECK).
  bool relightRotated(std::span<const Rgb> rotatedLight, int lightBands, const Vec3f& eye);
  /// The rows' radiance of the last relight (the part the texture multiplies, when textured).
  std::span<const Rgb> radiance() const {
    return encoding_ ? std::span<const Rgb>(encoded_) : relighter_.radiance();
  }
  /// The glossy lobe's radiance of the last relight, added untextured per pixel (empty unless
  /// the mesh is textured and the material glossy over matrices: render/base_colour.hpp).
  std::span<const Rgb> highlight() const { return glossy_ ? highlight_ : std::span<const Rgb>(); }

  /// Relights so far (not served from the last radiance), and of those the ones served from the
  /// view-collapsed transfer (only the light had changed): relight::Relighter's counts.
  int frames() const { return relighter_.frames(); }
  int lightOnlyFrames() const { return relighter_.lightOnlyFrames(); }

  /// The pixels of the last relight.
  ShadeFn shader() const;
  /// The pixels of other radiance at the rows (a reference's, drawn as PRT's would be; per
  /// vertex, untextured: it holds the texture already).
  ShadeFn shader(std::span<const Rgb> rowRadiance) const;

 private:
  const Mesh& mesh_;
  const Occluder* occluder_;  ///< null: rows only
  const Transfer& transfer_;
  Material material_;
  TexelRelight texels_;  ///< per texel: how the rows are relit and drawn
  const BaseColourTexture* texture_ = nullptr;
  relight::Relighter relighter_;
  std::optional<relight::Relighter> glossy_;  ///< the lobe, relit apart under a texture
  std::span<const Rgb> highlight_;
  std::optional<sh::IrradianceEncoding> encoding_;
  std::vector<Rgb> encoded_;  ///< the last relight's rows through encoding_

  relight::Surface surface() const;  ///< the rows' points: the vertices, or the texels' samples
};

}  // namespace prt::render

#include "transfer_options.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "cli.hpp"

namespace prt::cli {

void addTransferChoice(CLI::App* cmd, TransferChoice& c, const std::string& what) {
  cmd->add_option("--mode", c.mode,
                  "Transfer mode " + what +
                      ": unshadowed, shadowed or interreflected (default: the richest the bake "
                      "holds)");
  cmd->add_option("--transfer", c.layout,
                  "Layout " + what +
                      " when the bake holds both: vector or matrix (default: "
                      "matrix)");
}

const BakedTransfer& pickTransfer(const BakeFile& bake, const TransferChoice& c,
                                  const std::string& file) {
  std::optional<TransferMode> m;
  std::optional<TransferLayout> l;
  if (!c.mode.empty()) m = parseTransferMode(c.mode);
  if (!c.layout.empty()) l = parseTransferLayout(c.layout);
  return prt::pickTransfer(bake, m, l, file);
}

void addMaterialOption(CLI::App* cmd, std::string& spec, const std::string& what) {
  cmd->add_option("--material", spec,
                  "Material " + what +
                      " instead of the bake's: lambert, 'phong?exponent=32&ks=0.5' or "
                      "'ggx?roughness=0.3&ks=0.5', each with kd=r,g,b for the diffuse colour "
                      "(left out: the bake's); the lobe needs a matrix bake");
}

Material materialOption(const std::string& spec, const BakedTransfer& baked,
                        const std::string& file, const std::string& consequence) {
  const Material& own = baked.recipe.material;
  if (spec.empty()) return own;
  Material m = parseMaterial(spec);
  if (!m.diffuse) m.diffuse = own.diffuse;
  if (baked.recipe.glossyBounces(baked.transfer.layout()) &&
      !(m.lobe == own.lobe && m.specular == own.specular))
    warn(file + ": its bounces were baked off " + own.spec() + "; " + consequence);
  return m;
}

void warnLobeOnVectors(const Material& m, const BakedTransfer& baked, const std::string& file,
                       const std::string& consequence) {
  if (m.glossy() && !baked.transfer.isMatrix())
    warn(fmt::format("{}: the {} transfer is a vector (diffuse only); {}", file,
                     toString(baked.mode()), consequence));
}

Material materialFromGloss(const SurfaceGloss& g) {
  const auto clamp01 = [](float x) { return std::clamp(x, 0.0f, 1.0f); };
  Material m;
  m.specular = Rgb(clamp01(g.specular.x), clamp01(g.specular.y), clamp01(g.specular.z));
  if (g.model == SurfaceGloss::Model::Phong) {
    m.lobe.kind = LobeKind::Phong;
    m.lobe.exponent = std::clamp(double(g.exponent), 0.0, kMaxPhongExponent);
  } else {
    m.lobe.kind = LobeKind::Ggx;
    m.lobe.roughness = std::clamp(double(g.roughness), kMinGgxRoughness, 1.0);
  }
  return m;
}

}  // namespace prt::cli

#include "transfer_options.hpp"

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

const std::string& materialGrammar() {
  static const std::string g = std::string(
                                   "lambert, 'phong?exponent=32&ks=0.5' or "
                                   "'ggx?roughness=0.3&ks=0.5', each with kd=r,g,b for the "
                                   "diffuse colour. ") +
                               kGgxHelp;
  return g;
}

void addMaterialOption(CLI::App* cmd, std::string& spec, const std::string& what) {
  cmd->add_option("--material", spec,
                  "Material " + what +
                      " instead of the bake's (kd left out: the bake's; the lobe needs a matrix "
                      "bake): " +
                      materialGrammar());
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

}  // namespace prt::cli

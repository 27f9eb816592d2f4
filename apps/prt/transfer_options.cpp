#include "transfer_options.hpp"

#include <fmt/format.h>

#include "cli.hpp"
#include "prt/core/error.hpp"
#include "prt/io/haar_light_file.hpp"
#include "prt/io/light_file.hpp"
#include "prt/core/band_limits.hpp"

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

void warnLobeEnergyLoss(const Material& m, int bands, const std::string& file) {
  if (!m.glossy()) return;
  const double lost = m.lobe.energyBeyond(bands);
  if (lost <= kLobeEnergyLossWarning) return;
  // The fewest bands (up to the library's) that would keep the loss under the threshold.
  int enough = 0;
  for (int b = bands + 1; b <= bands::kMaxLibrary && !enough; ++b)
    if (m.lobe.energyBeyond(b) <= kLobeEnergyLossWarning) enough = b;
  warn(fmt::format("{}: the material's lobe ({}) loses {:.0f}% of its energy beyond {} bands: the "
                   "highlight will look broader and dimmer than the material's; {}",
                   file, m.spec(), 100 * lost, bands,
                   enough ? fmt::format("bake {} bands or use a rougher lobe", enough)
                          : std::string("use a rougher lobe")));
}

void refuseShLight(const std::string& light, const std::string& verb) {
  if (io::isLightFile(light))
    throw Error(light, std::string(io::isHaarLightFile(light) ? "is a Haar light file"
                                                              : "is an SH light file") +
                           "; prt " + verb +
                           " traces the environment itself (an image, a face folder or "
                           "builtin:NAME), whose radiance a light file's coefficients only "
                           "approximate");
}

}  // namespace prt::cli

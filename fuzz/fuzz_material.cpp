// The --material spec strings ("phong?exponent=32&ks=0.5", prt render/validate/reference/web/view
// and the bake file's stored material) through prt::parseMaterial. What a bake stores,
// Material::spec(), must read back: a parsed material whose spec does not is a finding.
#include <string>

#include "fuzz_common.hpp"
#include "prt/transfer/material.hpp"

PRT_FUZZ_TARGET({
  const prt::Material m = prt::parseMaterial(std::string(prt::fuzz::text(data, size)));
  try {
    prt::parseMaterial(m.spec());
  } catch (const prt::Error&) {
    __builtin_trap();
  }
})

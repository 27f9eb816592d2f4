// The --material spec strings ("phong?exponent=32&ks=0.5", prt render/validate/reference/web/view,
// and the material of bake files before version 4) through prt::parseMaterial. A parsed
// material's spec() (what prt info prints and --material takes back) must read back, and must
// pass checkMaterial, the check the bake file's writer and reader apply: a material that
// parses but would not be written is a finding.
#include <string>

#include "fuzz_common.hpp"
#include "prt/transfer/material.hpp"

PRT_FUZZ_TARGET({
  const prt::Material m = prt::parseMaterial(std::string(prt::fuzz::text(data, size)));
  try {
    prt::parseMaterial(m.spec());
    prt::checkMaterial(m);
  } catch (const prt::Error&) {
    __builtin_trap();
  }
})

#pragma once
// Relit probes: the SH of the light arriving at each probe of a grid under one light — what
// relightProbes (relight_probes.hpp) makes from a probe bake every time the light changes, and
// what a moving object is shaded from (issue 32). Row p holds B² RGB coefficients L'_p = M_p L
// (probe_grid.hpp gives the grid's layout: row x + nx·(y + ny·z)).

#include <cstddef>
#include <vector>

#include "prt/core/vec.hpp"
#include "prt/transfer/probe_grid.hpp"

namespace prt::relight {

struct ProbeLighting {
  ProbeGrid grid;
  int bands = 0;
  std::vector<Rgb> coefficients;  ///< probes × B², probe-major

  std::size_t coeffs() const { return std::size_t(bands) * std::size_t(bands); }
  const Rgb* probe(std::size_t r) const { return coefficients.data() + r * coeffs(); }
};

}  // namespace prt::relight

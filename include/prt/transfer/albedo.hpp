#pragma once
// The diffuse colour a relighting applies per row — the one rule every kernel, the renderer
// and the reference share: one value per row, one value for all rows, or none (white). A
// material that sets kd replaces it (Material::diffuseOr).

#include <cstddef>
#include <span>
#include <string>

#include "prt/core/error.hpp"
#include "prt/core/vec.hpp"

namespace prt {

class Albedo {
 public:
  /// Throws prt::Error("WHAT: N albedo values for R rows (expected one per row, one, or none)").
  Albedo(std::span<const Rgb> values, std::size_t rows, const std::string& what = "relight") {
    if (values.size() == rows && rows != 1)
      perRow_ = values.data();
    else if (values.size() == 1)
      uniform_ = values[0];
    else if (!values.empty())
      throw Error(what, std::to_string(values.size()) + " albedo values for " +
                            std::to_string(rows) + " rows (expected one per row, one, or none)");
  }
  /// The colour of row r.
  Rgb at(std::size_t r) const { return perRow_ ? perRow_[r] : uniform_; }
  /// The per-row values, or nullptr when one colour serves all rows.
  const Rgb* perRow() const { return perRow_; }
  /// The colour of every row when perRow() is null.
  Rgb uniform() const { return uniform_; }

 private:
  const Rgb* perRow_ = nullptr;
  Rgb uniform_{1.0f};
};

}  // namespace prt

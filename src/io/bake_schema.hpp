#pragma once
// The PRTKIT_radiance_transfer object of a bake file (extras.prtkit before version 5): how each transfer was made, as JSON — written one way (nlohmann,
// numbers as numbers that read back exactly, seeds beyond 2⁵³ as decimal strings for readers in
// JavaScript) and read with a check at every member, so a hand-edited file gives one line
// naming the member. Private to src/io; docs/formats-bake.md is the specification.

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "prt/core/error.hpp"
#include "prt/transfer/bake_settings.hpp"
#include "prt/transfer/cpca_settings.hpp"
#include "prt/transfer/material.hpp"
#include "prt/transfer/shape.hpp"

namespace prt::io::schema {

using nlohmann::json;

/// Reads members of untrusted JSON; every failure is prt::Error("NAME: WHERE.KEY ...").
class Reader {
 public:
  explicit Reader(std::string name) : name_(std::move(name)) {}
  const std::string& name() const { return name_; }
  [[noreturn]] void fail(const std::string& msg) const;

  const json& member(const json& obj, const std::string& key, const std::string& where) const;
  bool has(const json& obj, const std::string& key) const {
    return obj.is_object() && obj.contains(key);
  }
  double number(const json& obj, const std::string& key, const std::string& where) const;
  double numberOr(const json& obj, const std::string& key, double fallback,
                  const std::string& where) const;
  /// An integer in [lo, hi]: a JSON integer, an integral number, or (seeds) a decimal string.
  std::uint64_t integer(const json& obj, const std::string& key, const std::string& where,
                        double lo = 0, double hi = 18446744073709551615.0) const;
  std::string string(const json& obj, const std::string& key, const std::string& where) const;
  bool boolean(const json& obj, const std::string& key, const std::string& where) const;
  /// Runs f(); a prt::Error from it that does not already name the file is reworded as
  /// "NAME: WHERE: message".
  template <class F>
  auto within(const std::string& where, F&& f) const -> decltype(f());

 private:
  std::string name_;
};

/// An integer that JavaScript reads exactly: a number below 2⁵³, else a decimal string.
json exactInteger(std::uint64_t n);

/// The material as structured fields: {"type": "lambert"|"phong"|"ggx", "exponent" |
/// "roughness", "ks": [r, g, b], "kd": [r, g, b] (absent: the mesh's albedo)}.
json materialJson(const Material& m);
/// Reads the structured form, or (versions 2–3) the spec string ("phong?exponent=8&ks=0.4").
Material readMaterial(const json& v, const std::string& where, const Reader& r);

/// "response" of a matrix transfer: the material's SH kernels per band l < `bands`, what turns
/// the transferred incident light into exit radiance (transfer/prepared_material.hpp):
/// {"diffuse": [A_l/π], "lobe": [Λ_l] (zeros without a lobe)}. Written for engines and the
/// three.js module, which would otherwise have to integrate the lobe themselves; prtkit's own
/// reader recomputes the kernels from "material" and ignores it.
json responseJson(const Material& m, int bands);

/// "settings": the shape's layout, domain, bands and channels, and the recipe.
json settingsJson(const TransferShape& shape, const BakeRecipe& recipe);
/// Reads "settings" of a file of `version` into the recipe and the shape's layout, domain,
/// bands and channels (rows are the file's vertex range, set by the caller).
void readSettings(const json& o, const std::string& where, int version, const Reader& r,
                  BakeRecipe& recipe, TransferShape& shape);

json statsJson(const BakeStats& s);
/// Statistics are informative: absent or ill-typed members read as 0.
BakeStats readStats(const json& o, const std::string& where, const Reader& r);

/// The fit and error of a compressed transfer (members of "compressed" beside K and N).
void writeCpcaRecord(const CpcaRecord& c, json& compressed);
CpcaRecord readCpcaRecord(const json& compressed, const std::string& where, const Reader& r);

template <class F>
auto Reader::within(const std::string& where, F&& f) const -> decltype(f()) {
  try {
    return f();
  } catch (const Error& e) {
    const std::string msg = e.what();
    if (msg.rfind(name_, 0) == 0) throw;
    fail(where + ": " + msg);
  }
}

}  // namespace prt::io::schema

#pragma once
// "NAME?key=value&key=value" specifications: builtin scenes and environments
// (`builtin:sky?elevation=30`), materials (`phong?exponent=32&ks=0.5`). One parser, one set of
// messages: values are finite numbers (or r,g,b triples where asked), range-checked when read,
// and a key nobody read is an error naming the keys that exist.

#include <map>
#include <set>
#include <string>

#include "prt/core/vec.hpp"

namespace prt {

class Spec {
 public:
  /// Parses `full`; a leading `prefix` (e.g. "builtin:") is dropped from the name. Throws
  /// prt::Error("FULL: ...") for an item without '=', an empty key or a key given twice.
  explicit Spec(std::string full, const std::string& prefix = "");

  const std::string& name() const { return name_; }
  const std::string& full() const { return full_; }
  bool has(const std::string& key) const { return values_.count(key) != 0; }

  /// The number under `key`, or `def`; must be finite and in [lo, hi].
  double number(const std::string& key, double def, double lo, double hi);
  /// The same, and a whole number.
  int integer(const std::string& key, int def, int lo, int hi);
  /// "x" (grey) or "r,g,b", each in [lo, hi]; `def` when absent.
  Rgb colour(const std::string& key, Rgb def, double lo, double hi);
  /// Throws unless every key given was read: "unknown parameter 'k' (known: a, b)".
  void finish() const;

 private:
  double parseNumber(const std::string& key, const std::string& text) const;
  std::string full_, name_;
  std::map<std::string, std::string> values_;
  std::set<std::string> read_;
};

}  // namespace prt

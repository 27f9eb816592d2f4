#include "prt/core/spec.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "prt/core/error.hpp"

namespace prt {

namespace {

std::string shortNumber(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

Spec::Spec(std::string full, const std::string& prefix) : full_(std::move(full)) {
  std::string s = full_;
  if (!prefix.empty() && s.rfind(prefix, 0) == 0) s = s.substr(prefix.size());
  const auto q = s.find('?');
  name_ = s.substr(0, q);
  if (q == std::string::npos) return;
  const std::string query = s.substr(q + 1);
  std::size_t pos = 0;
  while (pos <= query.size()) {
    const auto amp = query.find('&', pos);
    const std::string item =
        query.substr(pos, amp == std::string::npos ? std::string::npos : amp - pos);
    if (!item.empty()) {
      const auto eq = item.find('=');
      if (eq == std::string::npos || eq == 0)
        throw Error(full_, "parameter '" + item + "' is not of the form key=value");
      // A key given twice has no one meaning ("exponent=16&exponent=32"): refuse, rather than
      // let the last one win silently.
      if (!values_.emplace(item.substr(0, eq), item.substr(eq + 1)).second)
        throw Error(full_, "parameter '" + item.substr(0, eq) + "' is given twice");
    }
    if (amp == std::string::npos) break;
    pos = amp + 1;
  }
}

double Spec::parseNumber(const std::string& key, const std::string& text) const {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(x))
    throw Error(full_, "parameter '" + key + "' needs a finite number, got '" + text + "'");
  return x;
}

double Spec::number(const std::string& key, double def, double lo, double hi) {
  read_.insert(key);
  const auto it = values_.find(key);
  if (it == values_.end()) return def;
  const double x = parseNumber(key, it->second);
  if (!(x >= lo && x <= hi))
    throw Error(full_, "parameter " + key + " must lie in [" + shortNumber(lo) + ", " +
                           shortNumber(hi) + "], got " + it->second);
  return x;
}

int Spec::integer(const std::string& key, int def, int lo, int hi) {
  const double x = number(key, def, lo, hi);
  if (x != std::floor(x)) throw Error(full_, "parameter " + key + " must be a whole number");
  return static_cast<int>(x);
}

Rgb Spec::colour(const std::string& key, Rgb def, double lo, double hi) {
  read_.insert(key);
  const auto it = values_.find(key);
  if (it == values_.end()) return def;
  std::vector<std::string> parts;
  std::string text = it->second, part;
  std::istringstream in(text);
  while (std::getline(in, part, ',')) parts.push_back(part);
  if (parts.size() != 1 && parts.size() != 3)
    throw Error(full_,
                "parameter " + key + " needs one value or three (r,g,b), got '" + text + "'");
  Rgb c;
  for (int k = 0; k < 3; ++k) {
    const double x = parseNumber(key, parts[parts.size() == 1 ? 0 : k]);
    if (!(x >= lo && x <= hi))
      throw Error(full_, "parameter " + key + " must lie in [" + shortNumber(lo) + ", " +
                             shortNumber(hi) + "], got " + text);
    c[k] = static_cast<float>(x);
  }
  return c;
}

void Spec::finish() const {
  for (const auto& [k, v] : values_)
    if (!read_.count(k)) {
      std::string known;
      for (const auto& r : read_) known += (known.empty() ? "" : ", ") + r;
      throw Error(full_, "unknown parameter '" + k + "'" +
                             (known.empty() ? " (it takes none)" : " (known: " + known + ")"));
    }
}

}  // namespace prt

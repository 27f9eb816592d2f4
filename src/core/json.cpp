#include "prt/core/json.hpp"

#include "prt/core/error.hpp"
#include "prt/core/limits.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace prt {

Json jsonFloat(float v) {
  if (!std::isfinite(v)) return nullptr;
  // The shortest decimal that reads back as v, then the double nearest that decimal, whose
  // shortest form (what nlohmann writes) is the same decimal.
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf - 1, v);
  *r.ptr = '\0';
  return std::strtod(buf, nullptr);
}

Json jsonFloats(const float* v, std::size_t n) {
  Json a = Json::array();
  for (std::size_t i = 0; i < n; ++i) a.push_back(jsonFloat(v[i]));
  return a;
}

namespace {

bool numbersOnly(const Json& a) {
  for (const Json& x : a)
    if (!x.is_number() && !x.is_null()) return false;
  return true;
}

void layout(const Json& v, int indent, int depth, std::string& out) {
  const std::string pad(static_cast<std::size_t>(indent) * (depth + 1), ' ');
  const std::string close(static_cast<std::size_t>(indent) * depth, ' ');
  if (v.is_object() && !v.empty()) {
    out += "{\n";
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (!first) out += ",\n";
      first = false;
      out += pad + Json(it.key()).dump() + ": ";
      layout(it.value(), indent, depth + 1, out);
    }
    out += "\n" + close + "}";
  } else if (v.is_array() && !v.empty() && !numbersOnly(v)) {
    out += "[\n";
    bool first = true;
    for (const Json& x : v) {
      if (!first) out += ",\n";
      first = false;
      out += pad;
      layout(x, indent, depth + 1, out);
    }
    out += "\n" + close + "]";
  } else if (v.is_array()) {
    out += "[";
    bool first = true;
    for (const Json& x : v) {
      if (!first) out += ", ";
      first = false;
      out += x.dump();
    }
    out += "]";
  } else {
    out += v.dump(-1, ' ', false, Json::error_handler_t::replace);
  }
}

}  // namespace

std::string formatJson(const Json& value, int indent) {
  if (indent <= 0) return value.dump(-1, ' ', false, Json::error_handler_t::replace);
  std::string out;
  layout(value, indent, 0, out);
  return out + "\n";
}

nlohmann::json parseJsonText(std::string_view text, const std::string& name) {
  checkJsonNesting(name, text);
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(name, "invalid JSON at byte " + std::to_string(e.byte));
  } catch (const nlohmann::json::exception&) {
    // out_of_range for a number too large for a double ("1e99999"; found by fuzz_light_json)
    throw Error(name, "invalid JSON (a number out of range)");
  }
}

}  // namespace prt

#include "prt/core/options.hpp"

#include <algorithm>

#include "prt/core/error.hpp"

namespace prt {

std::string optionName(OptionSpelling spelling, const std::string& name) {
  if (spelling == OptionSpelling::Cli) return "--" + name;
  std::string s = name;
  std::replace(s.begin(), s.end(), '-', '_');
  return s + "=";
}

std::string optionLabel(OptionSpelling spelling, const std::string& name) {
  std::string s = optionName(spelling, name);
  if (spelling == OptionSpelling::Python) s.pop_back();
  return s;
}

void checkOptionRange(OptionSpelling spelling, const std::string& name, long long value,
                      long long lo, long long hi) {
  if (value >= lo && value <= hi) return;
  throw Error(optionName(spelling, name) + (spelling == OptionSpelling::Cli ? " " : "") +
              std::to_string(value) + ": must be " + std::to_string(lo) + ".." +
              std::to_string(hi));
}

}  // namespace prt

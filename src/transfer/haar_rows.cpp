#include "prt/transfer/haar_rows.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "prt/core/error.hpp"
#include "prt/haar/resolution.hpp"

namespace prt::haar {

void pruneRow(const float* coeffs, int n, std::size_t terms, HaarRowKind kind, float* row,
              std::vector<std::pair<float, std::uint32_t>>& keys) {
  row[0] = float(static_cast<int>(kind));
  float* out = row + 1;
  // Every non-zero coefficient's key |c|·s, then the `keep` largest in linear time (ties to the
  // lower index: a strict order, so the choice is deterministic), then those in index order.
  const std::size_t count = coefficientCount(n);
  keys.clear();
  for (std::uint32_t k = 0; k < count; ++k)
    if (coeffs[k] != 0.0f) keys.push_back({std::abs(coeffs[k]) * float(supportSide(k, n)), k});
  const std::size_t keep = std::min(terms, keys.size());
  const auto larger = [](const std::pair<float, std::uint32_t>& a,
                         const std::pair<float, std::uint32_t>& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  };
  if (keep < keys.size())
    std::nth_element(keys.begin(), keys.begin() + std::ptrdiff_t(keep), keys.end(), larger);
  std::sort(keys.begin(), keys.begin() + std::ptrdiff_t(keep),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  float scale = 0;
  for (std::size_t t = 0; t < keep; ++t) scale = std::max(scale, std::abs(coeffs[keys[t].second]));
  std::size_t written = 0;
  for (std::size_t t = 0; t < keep; ++t) {
    const std::uint32_t k = keys[t].second;
    const int q = quantizeHaarValue(coeffs[k], scale);
    if (q == 0) continue;  // below the grid's step
    out[2 * written] = float(k);
    out[2 * written + 1] = dequantizeHaarValue(scale, q);
    ++written;
  }
  std::fill(out + 2 * written, out + 2 * terms, 0.0f);
}

int quantizeHaarValue(float value, float scale) {
  if (!(scale > 0)) return 0;
  const long q = std::lround(double(value) / double(scale) * kHaarValueSteps);
  return int(std::clamp<long>(q, -kHaarValueSteps, kHaarValueSteps));
}

float dequantizeHaarValue(float scale, int q) {
  return float(double(scale) * double(q) / kHaarValueSteps);
}

std::size_t storedHaarRowBytes(int n, int terms) {
  const std::size_t index = coefficientCount(n) <= 65536 ? 2 : 4;
  return 5 + std::size_t(terms) * (index + 2);
}

void checkRow(const float* header, int n, std::size_t terms, std::size_t r,
              const std::string& what) {
  if (header[0] != 0.0f && header[0] != 1.0f)
    throw Error(what + ": row " + std::to_string(r) +
                ": its kind must be 0 (occluded part) or 1 (visible part)");
  const float* row = header + 1;
  const double count = double(coefficientCount(n));
  double last = -1;
  for (std::size_t t = 0; t < terms; ++t) {
    const float index = row[2 * t], value = row[2 * t + 1];
    const auto fail = [&](const std::string& why) {
      throw Error(what + ": row " + std::to_string(r) + ", term " + std::to_string(t) + ": " + why);
    };
    if (!std::isfinite(value)) fail("the value is not finite");
    if (!(index >= 0 && double(index) < count) || std::floor(index) != index)
      fail("the index is not a coefficient of the " + std::to_string(n) + "² cube");
    if (value == 0.0f) {
      if (index != 0.0f) fail("a padding term (value 0) must have index 0");
      continue;
    }
    if (double(index) <= last) fail("the indices of the kept terms must ascend");
    last = index;
  }
}

}  // namespace prt::haar

#include "prt/transfer/haar_rows.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "prt/core/error.hpp"
#include "prt/haar/resolution.hpp"

namespace prt::haar {

void pruneRow(const float* coeffs, int n, std::size_t terms, float* out,
              std::vector<std::uint32_t>& order) {
  const std::size_t count = coefficientCount(n);
  order.clear();
  for (std::uint32_t k = 0; k < count; ++k)
    if (coeffs[k] != 0.0f) order.push_back(k);
  const std::size_t keep = std::min(terms, order.size());
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(keep), order.end(),
                    [&](std::uint32_t a, std::uint32_t b) {
                      const float x = std::abs(coeffs[a]) * float(supportSide(a, n));
                      const float y = std::abs(coeffs[b]) * float(supportSide(b, n));
                      return x != y ? x > y : a < b;
                    });
  std::sort(order.begin(), order.begin() + std::ptrdiff_t(keep));
  float scale = 0;
  for (std::size_t t = 0; t < keep; ++t) scale = std::max(scale, std::abs(coeffs[order[t]]));
  std::size_t written = 0;
  for (std::size_t t = 0; t < keep; ++t) {
    const int q = quantizeHaarValue(coeffs[order[t]], scale);
    if (q == 0) continue;  // below the grid's step
    out[2 * written] = float(order[t]);
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
  return 4 + std::size_t(terms) * (index + 2);
}

void checkRow(const float* row, int n, std::size_t terms, std::size_t r, const std::string& what) {
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

#include "prt/core/float_array.hpp"

#include <algorithm>

namespace prt {

FloatArray::FloatArray(std::vector<float> values) {
  auto owned = std::make_shared<std::vector<float>>(std::move(values));
  data_ = owned->data();
  size_ = owned->size();
  keeper_ = std::move(owned);
}

FloatArray FloatArray::zeros(std::size_t n) {
  return FloatArray(std::vector<float>(n, 0.0f));
}

FloatArray FloatArray::view(std::shared_ptr<const void> keeper, const float* data, std::size_t n) {
  FloatArray a;
  a.keeper_ = std::const_pointer_cast<void>(std::move(keeper));
  a.data_ = const_cast<float*>(data);  // never written through: owned_ is false
  a.size_ = n;
  a.owned_ = false;
  return a;
}

float* FloatArray::mutableData() {
  if (!owned_ || keeper_.use_count() > 1) {
    std::vector<float> copy(data_, data_ + size_);
    *this = FloatArray(std::move(copy));
  }
  return data_;
}

}  // namespace prt

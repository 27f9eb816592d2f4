#pragma once
// A contiguous array of floats that is either owned (a std::vector) or a read-only view into
// memory something else keeps alive — a mapped bake file, a numpy array — so that large transfer
// data is never copied just to be read. Copies share the storage (a pointer copy); the first
// write through mutableData() to storage that is shared or not ours copies it (copy on write),
// so an array behaves as a value: writing to one copy never changes another.
//
// Not thread-safe for writing: take mutableData() once, then write from as many threads as
// you like to disjoint elements.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace prt {

class FloatArray {
 public:
  FloatArray() = default;
  /// Takes the vector's storage (no copy).
  explicit FloatArray(std::vector<float> values);
  /// n zeros.
  static FloatArray zeros(std::size_t n);
  /// A read-only view of `data[0..n)`, kept alive by `keeper` (shared with every copy).
  static FloatArray view(std::shared_ptr<const void> keeper, const float* data, std::size_t n);

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const float* data() const { return data_; }
  std::span<const float> span() const { return {data_, size_}; }
  const float& operator[](std::size_t i) const { return data_[i]; }
  /// Writable storage: copies first when the storage is shared with another array or is a view.
  float* mutableData();
  /// True when the storage is a view of memory this array does not own (nothing copied yet).
  bool isView() const { return !owned_; }

 private:
  std::shared_ptr<void> keeper_;  ///< the vector (owned) or the view's keeper
  float* data_ = nullptr;
  std::size_t size_ = 0;
  bool owned_ = true;
};

}  // namespace prt

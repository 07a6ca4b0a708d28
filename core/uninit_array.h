#pragma once
// A fixed-size array whose elements are not initialised on allocation.
// std::vector<T>(n) zero-fills; for the decimator's per-vertex and per-face
// arrays that is hundreds of MB written by one thread before the parallel
// passes that fill them anyway (first-touch page faults then also happen
// in those passes, spread over the workers).
#include <cstddef>
#include <memory>

namespace hs::mesh {

template <class T>
class UninitArray {
 public:
  UninitArray() = default;
  explicit UninitArray(size_t n) : data_(std::make_unique_for_overwrite<T[]>(n)), size_(n) {}
  void reset(size_t n) {
    data_ = std::make_unique_for_overwrite<T[]>(n);
    size_ = n;
  }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  T* begin() { return data_.get(); }
  T* end() { return data_.get() + size_; }
  const T* begin() const { return data_.get(); }
  const T* end() const { return data_.get() + size_; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

 private:
  std::unique_ptr<T[]> data_;
  size_t size_ = 0;
};

}  // namespace hs::mesh

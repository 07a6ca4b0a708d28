#pragma once
// A fixed-size array whose elements are not initialised on allocation.
// std::vector<T>(n) zero-fills; for the decimator's per-vertex and per-face
// arrays that is hundreds of MB written by one thread before the parallel
// passes that fill them anyway (first-touch page faults then also happen
// in those passes, spread over the workers). Large arrays sit on huge
// pages (core/large_pages.h: a fault per 2 MiB instead of per 4 KiB).
// Elements must be trivially destructible: none is ever constructed.
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

#include "core/large_pages.h"

namespace hs {

template <class T>
class UninitArray {
  static_assert(std::is_trivially_destructible_v<T>, "elements are never constructed or destroyed");

 public:
  UninitArray() = default;
  explicit UninitArray(size_t n) { reset(n); }
  UninitArray(UninitArray&& o) noexcept : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
  UninitArray& operator=(UninitArray&& o) noexcept {
    if (this != &o) {
      release();
      data_ = std::exchange(o.data_, nullptr);
      size_ = std::exchange(o.size_, 0);
    }
    return *this;
  }
  UninitArray(const UninitArray&) = delete;
  UninitArray& operator=(const UninitArray&) = delete;
  ~UninitArray() { release(); }

  void reset(size_t n) {
    release();
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    data_ = n ? static_cast<T*>(allocateLarge(n * sizeof(T))) : nullptr;
    size_ = n;
  }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

 private:
  void release() {
    if (data_) freeLarge(data_, size_ * sizeof(T));
    data_ = nullptr, size_ = 0;
  }
  T* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace hs

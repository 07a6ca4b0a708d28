#pragma once
// Reading a PLY body in order (mesh/ply_reader.cpp): binary values of the
// eight types in either byte order, ASCII tokens, through the byte source a
// 4 MB piece at a time (a scan is never held whole, and a file that shrinks
// is an error).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "mesh/byte_source.h"
#include "mesh/ply_header.h"

namespace hs::mesh::ply {

// One binary value of type `t` at `p`, byte-swapped when `swap`.
inline double decodeValue(Type t, const char* p, bool swap) {
  auto get = [&](auto tag) {
    decltype(tag) v;
    char b[sizeof v];
    std::memcpy(b, p, sizeof v);
    if (swap) std::reverse(b, b + sizeof v);
    std::memcpy(&v, b, sizeof v);
    return double(v);
  };
  switch (t) {
    case Type::Int8: return get(int8_t{});
    case Type::UInt8: return get(uint8_t{});
    case Type::Int16: return get(int16_t{});
    case Type::UInt16: return get(uint16_t{});
    case Type::Int32: return get(int32_t{});
    case Type::UInt32: return get(uint32_t{});
    case Type::Float32: return get(float{});
    case Type::Float64: return get(double{});
  }
  return 0.0;
}

// Sequential reading of the body through the byte source, in 4 MB pieces
// (a scan is never held whole, and a file that shrinks is an error).
class Body {
 public:
  Body(const ByteSource& src, uint64_t start, bool ascii, bool swap)
      : src_(src), base_(start), ascii_(ascii), swap_(swap) {}

  uint64_t offset() const { return base_ + pos_; }
  std::string error;

  // Binary: the next value of `t` as double / as a whole number.
  bool value(Type t, double& v) {
    if (ascii_) return asciiNumber(v);
    const char* p = take(size_t(ply::typeSize(t)));
    if (!p) return false;
    v = decode(t, p);
    return true;
  }
  bool integer(Type t, int64_t& v) {
    double d = 0.0;
    if (!value(t, d)) return false;
    if (t == Type::Float32 || t == Type::Float64 || ascii_) {
      if (!(d == std::floor(d)) || std::abs(d) > 9.0e15) {
        error = "'" + std::to_string(d) + "' is not a whole number";
        return false;
      }
    }
    v = int64_t(d);
    return true;
  }
  // Whether anything but white space (ASCII) or any byte (binary) is left.
  bool hasData() {
    if (!ascii_) return offset() < src_.size();
    for (;;) {
      if (pos_ >= view_.size() && !refillAtMost(1)) return false;
      const char c = view_[pos_];
      if (c != ' ' && c != '\t' && c != '\r' && c != '\n') return true;
      ++pos_;
    }
  }
  // The next `n` bytes of binary data (valid until the next call), or
  // nullptr with `error` at the end of the file.
  const char* block(size_t n) { return take(n); }
  static constexpr size_t kPieceBytes = size_t(4) << 20;
  // Binary: up to `n` bytes at the cursor without taking them (valid until
  // the next call); `available` says how many there are (fewer at the end
  // of the file). advance() then takes what the caller used of them.
  const char* window(size_t n, size_t& available) {
    available = 0;
    if (!refillAtMost(n)) return nullptr;
    available = std::min(n, view_.size() - pos_);
    return view_.data() + pos_;
  }
  void advance(size_t n) { pos_ += n; }
  // Skips `n` bytes of fixed-size binary data.
  bool skip(uint64_t n) {
    while (n > 0) {
      const size_t step = size_t(std::min<uint64_t>(n, kPiece));
      if (!take(step)) return false;
      n -= step;
    }
    return true;
  }

 private:
  static constexpr size_t kPiece = size_t(4) << 20;

  // `n` bytes at the cursor, valid until the next call; nullptr at the end.
  const char* take(size_t n) {
    if (view_.size() - pos_ < n && !refill(n)) return nullptr;
    const char* p = view_.data() + pos_;
    pos_ += n;
    return p;
  }
  bool refill(size_t n) {
    const uint64_t at = base_ + pos_;
    const uint64_t left = src_.size() > at ? src_.size() - at : 0;
    if (left < n) {
      error = "cut short: the file ends at byte " + std::to_string(src_.size()) + ", inside this row";
      return false;
    }
    const size_t want = size_t(std::min<uint64_t>(left, std::max(n, kPiece)));
    if (!src_.read(at, want, storage_, view_, error)) return false;
    base_ = at;
    pos_ = 0;
    return true;
  }
  double decode(Type t, const char* p) const { return decodeValue(t, p, swap_); }
  bool asciiNumber(double& v) {
    // Skip separators, then read one token (at most 64 characters).
    for (;;) {
      if (pos_ >= view_.size() && !refillAtMost(1)) {
        error = "cut short: the file ends at byte " + std::to_string(src_.size()) + ", inside this row";
        return false;
      }
      const char c = view_[pos_];
      if (c != ' ' && c != '\t' && c != '\r' && c != '\n') break;
      ++pos_;
    }
    if (view_.size() - pos_ < 64) refillAtMost(64);
    const char* b = view_.data() + pos_;
    const char* e = b;
    const char* end = view_.data() + view_.size();
    while (e < end && *e != ' ' && *e != '\t' && *e != '\r' && *e != '\n') ++e;
    if (e - b > 64) {
      error = "a value longer than 64 characters";
      return false;
    }
    const auto r = std::from_chars(b, e, v);
    if (r.ec != std::errc() || r.ptr != e) {
      error = "'" + std::string(b, size_t(e - b)) + "' is not a number";
      return false;
    }
    pos_ += size_t(e - b);
    return true;
  }
  // Makes at least `n` bytes (or what is left of the file) available.
  bool refillAtMost(size_t n) {
    const uint64_t at = base_ + pos_;
    if (at >= src_.size()) return false;
    const uint64_t left = src_.size() - at;
    if (view_.size() - pos_ >= std::min<uint64_t>(n, left)) return true;
    const size_t want = size_t(std::min<uint64_t>(left, std::max(n, kPiece)));
    std::string e;
    if (!src_.read(at, want, storage_, view_, e)) {
      error = e;
      return false;
    }
    base_ = at;
    pos_ = 0;
    return true;
  }

  const ByteSource& src_;
  uint64_t base_;
  size_t pos_ = 0;
  bool ascii_, swap_;
  std::string storage_;
  std::string_view view_;
};

}  // namespace hs::mesh::ply

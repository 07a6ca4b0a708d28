#pragma once
// Fixed-size fields of the foliage's blobs (cells, store.h; impostor
// images, impostor_images.h) and of the impostor key's bytes
// (scene/impostor_key.h), copied by memcpy: little endian on the hosts the
// project builds for (x86-64, arm64), which is the files' byte order.
#include <cstdint>
#include <cstring>
#include <vector>

namespace hs::foliage::byte_io {

// Appends v's bytes to `out`.
template <class T>
void put(std::vector<uint8_t>& out, const T& v) {
  const size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof(T));
}

// The T whose bytes start at `p`.
template <class T>
T get(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

}  // namespace hs::foliage::byte_io

#include "core/image.h"

#include <algorithm>
#include <cstring>

namespace hs {

void copyRowsFlipped(const void* src, void* dst, size_t rowBytes, size_t rows) {
  const auto* s = static_cast<const uint8_t*>(src);
  auto* d = static_cast<uint8_t*>(dst);
  if (s == d) {
    for (size_t y = 0; y < rows / 2; ++y)
      std::swap_ranges(d + y * rowBytes, d + (y + 1) * rowBytes, d + (rows - 1 - y) * rowBytes);
    return;
  }
  for (size_t y = 0; y < rows; ++y) std::memcpy(d + y * rowBytes, s + (rows - 1 - y) * rowBytes, rowBytes);
}

}  // namespace hs

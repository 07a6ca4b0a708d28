#pragma once
// GPU memory the renderer holds: the sum of its resource registry (every
// buffer and texture it allocated), what the render benchmarks divide by
// an instance count.
#include <cstddef>

#include "render/renderer.h"

namespace hs::bench {

inline size_t registryBytes(const render::Renderer& r) {
  size_t n = 0;
  for (const render::GpuAllocation& a : r.resourceRegistry()) n += a.bytes;
  return n;
}

}  // namespace hs::bench

#pragma once
// The size of one instance of an instanced source on the GPU (render/
// instanced_source.h GpuInstance, which asserts it), for what the editor
// and reports say an instance costs without seeing the renderer's inside.
#include <cstddef>

namespace hs::render {

inline constexpr size_t kGpuInstanceBytes = 32;

}  // namespace hs::render

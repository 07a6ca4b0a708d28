#pragma once
// Whether a frame ran a pass (FrameStats::passes), and whether the
// renderer holds a resource (its registry), for the tests of "a pass only
// when its effect is on": by a part of the name ("bloom" matches
// "bloom_down0[left]").
#include <string>

#include "render/renderer.h"

namespace hs::test {

inline bool passRan(const render::FrameStats& s, const std::string& part) {
  for (const render::PassStats& p : s.passes)
    if (p.name.find(part) != std::string::npos) return true;
  return false;
}

// The name of the first GPU allocation the renderer holds whose name holds
// `part`; empty when there is none.
inline std::string allocationNamed(const render::Renderer& r, const std::string& part) {
  for (const render::GpuAllocation& a : r.resourceRegistry())
    if (a.name.find(part) != std::string::npos) return a.name;
  return {};
}

}  // namespace hs::test

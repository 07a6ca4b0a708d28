#pragma once
// Whether a frame ran a pass (FrameStats::passes), for the tests of "a
// pass only when its effect is on": by a part of its name ("bloom" matches
// "bloom_down0[left]").
#include <string>

#include "render/renderer.h"

namespace hs::test {

inline bool passRan(const render::FrameStats& s, const std::string& part) {
  for (const render::PassStats& p : s.passes)
    if (p.name.find(part) != std::string::npos) return true;
  return false;
}

}  // namespace hs::test

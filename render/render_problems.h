#pragma once
// Everything the renderer refused or clamped since the last call, for the
// user: materials it could not draw as set, shadow settings it clamped,
// light clusters over the cap, lenses depth of field refused, a LUT left
// out of the frame, cluster pages that could not be read (each list
// reports a problem once, when it starts). The CLI prints them as
// warnings, the editor's Messages dock shows them.
#include <string>
#include <vector>

#include "render/renderer.h"

namespace hs::render {

inline std::vector<std::string> takeRenderProblems(Renderer& r) {
  std::vector<std::string> out = r.takeMaterialProblems();
  for (auto take : {&Renderer::takeShadowProblems, &Renderer::takeLightProblems, &Renderer::takeDofProblems,
                     &Renderer::takeLutProblems, &Renderer::takeClusterProblems})
    for (std::string& p : (r.*take)()) out.push_back(std::move(p));
  return out;
}

}  // namespace hs::render

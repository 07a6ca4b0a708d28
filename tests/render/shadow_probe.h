#pragma once
// The shadow tests' probe (test_shadows, test_local_shadows): each pixel's
// shadowed state, read from two HDR frames, and its world position read
// back from the depth buffer, for the CPU ray cast to check.
#include <algorithm>
#include <vector>

#include <glm/glm.hpp>

#include "render/offscreen_renderer.h"
#include "scene/scene_state.h"

namespace hs::test {

// What the shadows do to each pixel: the HDR image with shadows divided by
// the one without (ambient off, so the scene's lights are all the light);
// -1 where the surface gets too little light to tell (sky, faces turned
// away, grazing light, outside a spot's cone). Also the world position of
// each pixel from its depth.
struct ShadowProbe {
  int width = 0, height = 0;
  std::vector<float> visibility;   // top row first
  std::vector<glm::dvec3> world;   // top row first; only where visibility >= 0
};

inline ShadowProbe probeShadows(render::OffscreenRenderer& r, scene::SceneState s, const render::RenderView& view,
                                const render::RenderOptions& options = {}) {
  s.settings.ambientIntensity = 0.0f;
  ShadowProbe p;
  p.width = view.width;
  p.height = view.height;
  const bool shadows = s.settings.shadows;
  s.settings.shadows = false;
  const hs::Image lit = r.render(s, view, true, nullptr, options);
  s.settings.shadows = shadows;
  render::RenderOptions o = options;
  o.keepDepth = true;
  const hs::Image shaded = r.render(s, view, true, nullptr, o);
  std::vector<float> depth(size_t(view.width) * size_t(view.height));
  r.renderer().readDepth(depth.data());
  float maxLit = 0.0f;
  for (size_t i = 0; i < depth.size(); ++i) maxLit = std::max(maxLit, lit.rgbaF[i * 4 + 1]);
  const glm::dmat4 inv = glm::inverse(view.projection() * glm::dmat4(view.viewRotation()));
  p.visibility.assign(depth.size(), -1.0f);
  p.world.assign(depth.size(), glm::dvec3(0.0));
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const size_t i = size_t(y) * size_t(view.width) + size_t(x);
      const float d = depth[size_t(view.height - 1 - y) * size_t(view.width) + size_t(x)];  // bottom row first
      const float u = lit.rgbaF[i * 4 + 1];
      if (d <= 0.0f || u < 0.01f * maxLit) continue;
      p.visibility[i] = shaded.rgbaF[i * 4 + 1] / u;
      const glm::dvec4 ndc((x + 0.5) / view.width * 2.0 - 1.0, 1.0 - (y + 0.5) / view.height * 2.0, double(d), 1.0);
      const glm::dvec4 e = inv * ndc;
      p.world[i] = view.eye + glm::dvec3(e) / e.w;
    }
  return p;
}

}  // namespace hs::test

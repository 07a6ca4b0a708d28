#pragma once
// A stereo pair looking straight down at a grey plane (unlit: its colour is
// the picture), the eyes set apart for a disparity of exactly
// `disparityPx` pixels at the plane, and how much of one eye's ink the
// other has moved by a shift: for the stylised effects that attach one
// eye's pattern to the surfaces the other sees (stippling, error
// diffusion; render/passes/stipple_passes.h, stylised_passes.h).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "look_from.h"
#include "mesh/primitives.h"
#include "render/offscreen_renderer.h"
#include "render/output_target.h"
#include "render/renderer.h"
#include "scene_parts.h"
#include "two_shots.h"

namespace hs::test {

struct StereoPlane {
  static constexpr int kWidth = 320, kHeight = 180;
  static constexpr double kDistance = 10.0;
  scene::SceneState scene;
  render::RenderView left, right;

  explicit StereoPlane(double disparityPx, glm::vec3 grey = glm::vec3(0.25f)) {
    scene.settings.showGrid = false;
    scene.settings.antialiasing = scene::Antialiasing::None;
    scene.settings.tonemap = scene::Tonemap::None;
    addMeshAsset(scene, 1, "Plane", mesh::gridPlane(200.0f, 1), grey, 1.0f, true);
    addMeshEntity(scene, 1, "Plane", 1);
    render::RenderView v;
    v.width = kWidth;
    v.height = kHeight;
    v.fovY = glm::radians(55.0);
    v.eye = {0.0, 0.0, kDistance};
    v.orientation = lookFrom(v.eye, {0.0, 0.001, 0.0}).rotation;
    const double focalPx = 0.5 * kHeight / std::tan(0.5 * v.fovY);
    const double baseline = disparityPx * kDistance / focalPx;
    left = shiftedSideways(v, -0.5 * baseline);
    right = shiftedSideways(v, 0.5 * baseline);
  }
  // A ball between the eyes and the plane: the right eye sees plane the
  // left eye does not.
  void addBall() {
    addMeshAsset(scene, 2, "Ball", mesh::uvSphere(1.0f, 24, 12), {0.6f, 0.6f, 0.6f}, 1.0f, true);
    addMeshEntity(scene, 2, "Ball", 2, {0.0, 0.0, 5.0});
  }
};

// Both eyes of `state` in one frame (Renderer::renderViews), read back.
inline std::pair<Image, Image> renderPair(render::OffscreenRenderer& r, const scene::SceneState& state,
                                          const render::RenderView& left, const render::RenderView& right) {
  r.makeCurrent();
  render::OutputTarget outs[2];
  std::vector<render::ViewTarget> targets;
  for (int i = 0; i < 2; ++i) {
    outs[i].ensure(left.width, left.height);
    targets.push_back({i ? right : left, outs[i].fbo(), i ? "right" : "left"});
  }
  r.renderer().renderViews(state, targets);
  return {r.renderer().readDisplay(outs[0].fbo(), left.width, left.height),
          r.renderer().readDisplay(outs[1].fbo(), left.width, left.height)};
}

// The share of `b`'s ink (red under 128) that `a` has `shift` pixels
// further right, where both are in frame.
inline double inkMatched(const Image& a, const Image& b, int shift) {
  size_t ink = 0, both = 0;
  for (int y = 0; y < b.height; ++y)
    for (int x = std::max(0, -shift); x < std::min(b.width, b.width - shift); ++x) {
      if (b.rgba8[(size_t(y) * b.width + x) * 4] >= 128) continue;
      ++ink;
      both += a.rgba8[(size_t(y) * a.width + x + shift) * 4] < 128;
    }
  return double(both) / double(std::max<size_t>(ink, 1));
}

// The shift in [-range, range] under which the most of `b`'s ink is `a`'s.
inline int bestInkShift(const Image& a, const Image& b, int range = 30) {
  int best = 0;
  for (int shift = -range; shift <= range; ++shift)
    if (inkMatched(a, b, shift) > inkMatched(a, b, best)) best = shift;
  return best;
}

}  // namespace hs::test

#include "app/timeline_path_overlay.h"

#include <algorithm>
#include <cmath>

#include "app/overlay_builder.h"
#include "sequencer/key_edit.h"

namespace hs::app {

namespace {

constexpr int kPathSamples = 240;
constexpr int kMotionSamples = 240;

// A diamond marker facing the view, `pixels` across at its distance.
void marker(render::Overlay& o, const glm::dvec3& p, const render::RenderView& view, double pixels, const glm::vec4& c) {
  const double depth = glm::dot(p - view.eye, view.forward());
  if (depth <= view.nearClip) return;
  const double s = view.pixelSizeAt(depth) * pixels * 0.5;
  const glm::dvec3 r = view.right() * s, u = view.up() * s;
  o.triangle(p + u, p - r, p - u, c);
  o.triangle(p + u, p - u, p + r, c);
}

glm::dvec3 parentWorld(const scene::SceneState& s, scene::EntityId id, const glm::dvec3& local) {
  const scene::Entity* e = s.find(id);
  if (!e || e->parent == scene::kNoEntity) return local;
  return glm::dvec3(s.worldMatrix(e->parent) * glm::dvec4(local, 1.0));
}

}  // namespace

void buildTimelineOverlay(const scene::SceneState& base, const sequencer::CompiledSequence& compiled,
                          const std::vector<scene::EntityId>& selection, double time, const render::RenderView& view,
                          render::Overlay& out) {
  const sequencer::Sequence& seq = compiled.sequence();
  const glm::vec4 pathColor = overlayColor({0.95f, 0.8f, 0.3f}, 0.85f, base.settings);
  const glm::vec4 faint = overlayColor({0.95f, 0.8f, 0.3f}, 0.45f, base.settings);
  const glm::vec4 pointColor = overlayColor({1.0f, 0.55f, 0.12f}, 1.0f, base.settings);
  const glm::vec4 keyColor = overlayColor({1.0f, 1.0f, 1.0f}, 1.0f, base.settings);
  const glm::vec4 nowColor = overlayColor({0.3f, 1.0f, 0.45f}, 1.0f, base.settings);
  const glm::vec4 aimColor = overlayColor({0.35f, 0.85f, 1.0f}, 0.9f, base.settings);
  auto selected = [&](scene::EntityId id) { return std::find(selection.begin(), selection.end(), id) != selection.end(); };
  const double t0 = sequencer::frameTime(seq.startFrame, seq.rate), t1 = sequencer::frameTime(seq.endFrame, seq.rate);
  for (size_t i = 0; i < seq.bindings.size(); ++i) {
    const sequencer::Binding& b = seq.bindings[i];
    if (!base.find(b.entity)) continue;
    const bool sel = selected(b.entity);
    if (b.path) {
      const sequencer::PathSampler* sampler = compiled.pathSampler(i);
      if (!sampler || sampler->empty()) continue;
      const double length = sampler->length();
      glm::dvec3 prev = sampler->position(0.0);
      for (int k = 1; k <= kPathSamples; ++k) {
        const glm::dvec3 p = sampler->position(length * k / kPathSamples);
        out.line(prev, p, sel ? pathColor : faint);
        prev = p;
      }
      for (const glm::dvec3& p : b.path->path.points) marker(out, p, view, sel ? 11.0 : 8.0, pointColor);
      // Where the progress keys put the camera.
      for (const sequencer::ScalarKey& k : b.path->progress.keys)
        marker(out, sampler->position(std::clamp(k.value, 0.0, 1.0) * length), view, 7.0, keyColor);
      // Where the camera is now, and for the path being edited what it looks at.
      const sequencer::PathPose now = sequencer::evaluatePath(*b.path, *sampler, time);
      marker(out, now.position, view, sel ? 13.0 : 9.0, nowColor);
      if (sel && b.path->aim == sequencer::PathAim::Point) {
        out.line(now.position, b.path->targetPoint, aimColor);
        marker(out, b.path->targetPoint, view, 10.0, aimColor);
      }
      continue;
    }
    if (!sel) continue;
    const std::vector<double> keyTimes = sequencer::keyTimes(seq, b.entity, "transform.translation");
    if (keyTimes.empty()) continue;
    // Motion over the range (and out to the keys beyond it), in world space
    // through the parent as it stands.
    const double a = std::min(t0, keyTimes.front()), z = std::max(t1, keyTimes.back());
    auto at = [&](double t) -> std::optional<glm::dvec3> {
      const auto v = sequencer::evaluate(compiled, t).vector(b.entity, "transform.translation");
      if (!v) return std::nullopt;
      return parentWorld(base, b.entity, *v);
    };
    std::optional<glm::dvec3> prev = at(a);
    for (int k = 1; k <= kMotionSamples && prev; ++k) {
      const auto p = at(a + (z - a) * k / kMotionSamples);
      if (!p) break;
      out.line(*prev, *p, pathColor);
      prev = p;
    }
    for (double t : keyTimes)
      if (const auto p = at(t)) marker(out, *p, view, 9.0, keyColor);
  }
}

}  // namespace hs::app

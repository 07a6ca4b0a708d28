#include "app/overlay_builder.h"

#include <algorithm>
#include <cmath>

#include "app/emitter_overlay.h"
#include "app/overlay_shapes.h"
#include "scene/light_units.h"
#include "scene/transform.h"
#include "scene/world_bounds.h"

namespace hs::app {
namespace {

constexpr double kGlyphPixels = 22.0;

float inverseAces(float y) {
  // Inverse of x(ax+b)/(x(cx+d)+e): a quadratic in x.
  constexpr float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  y = std::clamp(y, 0.0f, 0.97f);
  const float qa = a - c * y, qb = b - d * y, qc = -e * y;
  return (-qb + std::sqrt(qb * qb - 4.0f * qa * qc)) / (2.0f * qa);
}

void cameraGlyph(render::Overlay& o, const scene::Entity& e, const glm::dmat4& world, const render::RenderView& view,
                 const glm::vec4& col) {
  const scene::Transform t = scene::Transform::fromMatrix(world);
  const double s = worldPerPixels(view, t.translation, kGlyphPixels * 2.0);
  if (s <= 0.0) return;
  const glm::dvec3 f = t.rotation * glm::dvec3(0, 0, -1), r = t.rotation * glm::dvec3(1, 0, 0),
                   u = t.rotation * glm::dvec3(0, 1, 0);
  const double tanHalf = std::tan(glm::radians(e.camera ? e.camera->verticalFovDeg : 50.0) * 0.5);
  const double hh = s * tanHalf, hw = hh * 16.0 / 9.0;
  const glm::dvec3 apex = t.translation, base = apex + f * s;
  const glm::dvec3 corners[4] = {base - r * hw - u * hh, base + r * hw - u * hh, base + r * hw + u * hh,
                                 base - r * hw + u * hh};
  for (int i = 0; i < 4; ++i) {
    o.line(apex, corners[i], col);
    o.line(corners[i], corners[(i + 1) % 4], col);
  }
  // The "up" notch tells which way the image is upright.
  const glm::dvec3 top = base + u * (hh * 1.6);
  o.triangle(base - r * (hw * 0.5) + u * (hh * 1.1), base + r * (hw * 0.5) + u * (hh * 1.1), top, col);
}

void lightGlyph(render::Overlay& o, const scene::Entity& e, const glm::dmat4& world, const render::RenderView& view,
                const glm::vec4& col, bool selected) {
  const glm::dvec3 p(world[3]);
  const double s = worldPerPixels(view, p, kGlyphPixels);
  if (s <= 0.0) return;
  const glm::dvec3 vr = view.right(), vu = view.up();
  circle(o, p, vr, vu, s * 0.5, col, 20);
  for (int i = 0; i < 8; ++i) {
    const double a = i * M_PI / 4.0;
    const glm::dvec3 d = vr * std::cos(a) + vu * std::sin(a);
    o.line(p + d * (s * 0.7), p + d * s, col);
  }
  if (e.light->type == scene::Light::Type::Sun) {
    // Suns shine along their local -Z.
    const glm::dvec3 dir = glm::normalize(glm::dvec3(world * glm::dvec4(0, 0, -1, 0)));
    const glm::dvec3 tip = p + dir * (s * 3.5);
    o.line(p + dir * (s * 0.5), tip, col);
    glm::dvec3 side = glm::cross(dir, view.forward());
    if (glm::length(side) < 1e-6) side = vr;
    side = glm::normalize(side);
    o.triangle(tip + dir * (s * 0.5), tip + side * (s * 0.25), tip - side * (s * 0.25), col);
  } else if (selected) {
    const glm::vec4 faint(col.r, col.g, col.b, col.a * 0.35f);
    circle(o, p, glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), double(e.light->range), faint, 64);
  }
}

void emptyGlyph(render::Overlay& o, const glm::dmat4& world, const render::RenderView& view, const glm::vec4& col) {
  const glm::dvec3 p(world[3]);
  const double s = worldPerPixels(view, p, kGlyphPixels * 0.8);
  if (s <= 0.0) return;
  for (int i = 0; i < 3; ++i) {
    glm::dvec3 a(0.0);
    a[i] = s;
    o.line(p - a, p + a, col);
  }
}

}  // namespace

glm::vec4 overlayColor(const glm::vec3& display, float alpha, const scene::SceneSettings& settings) {
  const float inv = float(1.0 / std::max(scene::exposureMultiplier(settings.exposureEv100), 1e-9));
  if (settings.tonemap != scene::Tonemap::Aces) return {display * inv, alpha};
  return {inverseAces(display.r) * inv, inverseAces(display.g) * inv, inverseAces(display.b) * inv, alpha};
}

void buildSceneOverlay(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
                       const render::RenderView& view, render::Overlay& out) {
  const glm::vec4 glyph = overlayColor({0.62f, 0.64f, 0.68f}, 0.9f, state.settings);
  const glm::vec4 highlight = overlayColor({1.0f, 0.55f, 0.12f}, 1.0f, state.settings);
  const glm::vec4 subtree = overlayColor({1.0f, 0.55f, 0.12f}, 0.45f, state.settings);
  auto isSelected = [&](scene::EntityId id) { return std::find(selection.begin(), selection.end(), id) != selection.end(); };

  for (const auto& [id, e] : state.entities) {
    if (e.mesh || !state.effectivelyVisible(id)) continue;
    const glm::dmat4 world = state.worldMatrix(id);
    const bool sel = isSelected(id);
    const glm::vec4& col = sel ? highlight : glyph;
    if (e.camera)
      cameraGlyph(out, e, world, view, col);
    else if (e.light)
      lightGlyph(out, e, world, view, col, sel);
    else if (e.particles)
      emitterGlyph(out, state, id, view, col, sel);
    else
      emptyGlyph(out, world, view, col);
  }

  for (scene::EntityId id : selection) {
    const scene::Entity* e = state.find(id);
    if (!e) continue;
    if (e->mesh) {
      const scene::MeshAsset* a = state.findAsset(e->mesh->mesh);
      if (a && a->data && !a->data->positions.empty()) {
        const mesh::Bounds b = a->data->bounds();
        box(out, state.worldMatrix(id), glm::dvec3(b.min), glm::dvec3(b.max), highlight);
      }
    }
    if (!e->children.empty()) {
      const scene::WorldBox wb = scene::worldBounds(state, {id});
      if (!wb.empty) box(out, glm::dmat4(1.0), wb.min, wb.max, subtree);
    }
  }
}

scene::EntityId pickGlyph(const scene::SceneState& state, const render::RenderView& view, const glm::dvec2& pixel,
                          double radiusPixels) {
  scene::EntityId best = scene::kNoEntity;
  double bestDistance = radiusPixels;
  for (const auto& [id, e] : state.entities) {
    if (e.mesh || !state.effectivelyVisible(id)) continue;
    glm::dvec2 p;
    if (!view.project(glm::dvec3(state.worldMatrix(id)[3]), p)) continue;
    const double d = glm::length(p - pixel);
    if (d <= bestDistance) {
      bestDistance = d;
      best = id;
    }
  }
  return best;
}

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + ab * t));
}

}  // namespace hs::app

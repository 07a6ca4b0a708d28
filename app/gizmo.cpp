#include "app/gizmo.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "app/overlay_builder.h"
#include "scene/operations.h"
#include "scene/transform.h"

namespace hs::app {
namespace {

// Handle proportions, in units of GizmoFrame::length.
constexpr double kShaftStart = 0.18, kShaftEnd = 1.0, kTipEnd = 1.22, kTipRadius = 0.06;
constexpr double kPlaneLo = 0.28, kPlaneHi = 0.5, kViewHalf = 0.08;
constexpr double kRingRadius = 1.0, kViewRingRadius = 1.2;
constexpr double kScaleCube = 0.065, kUniformCube = 0.1;
constexpr int kRingSegments = 64;

const glm::vec3 kAxisColors[3] = {{0.93f, 0.22f, 0.2f}, {0.38f, 0.8f, 0.16f}, {0.2f, 0.45f, 0.98f}};
const glm::vec3 kHoverColor{1.0f, 0.86f, 0.2f};
const glm::vec3 kViewColor{0.86f, 0.87f, 0.9f};

int axisIndex(GizmoHandle h) {
  switch (h) {
    case GizmoHandle::X: return 0;
    case GizmoHandle::Y: return 1;
    case GizmoHandle::Z: return 2;
    default: return -1;
  }
}
// The two frame axes spanning a plane handle.
bool planeAxes(GizmoHandle h, int& a, int& b) {
  switch (h) {
    case GizmoHandle::XY: a = 0, b = 1; return true;
    case GizmoHandle::YZ: a = 1, b = 2; return true;
    case GizmoHandle::ZX: a = 2, b = 0; return true;
    default: return false;
  }
}
GizmoHandle axisHandle(int i) { return i == 0 ? GizmoHandle::X : i == 1 ? GizmoHandle::Y : GizmoHandle::Z; }
GizmoHandle planeHandle(int i) { return i == 0 ? GizmoHandle::XY : i == 1 ? GizmoHandle::YZ : GizmoHandle::ZX; }

double snapTo(double v, double step) { return step > 0.0 ? std::round(v / step) * step : v; }

double wrapAngle(double a) {
  while (a > M_PI) a -= 2.0 * M_PI;
  while (a <= -M_PI) a += 2.0 * M_PI;
  return a;
}

// An axis seen nearly end-on cannot be dragged meaningfully: fade it and
// leave it out of picking.
bool axisEndOn(const render::RenderView& view, const glm::dvec3& origin, const glm::dvec3& axis) {
  return std::abs(glm::dot(glm::normalize(origin - view.eye), axis)) > 0.985;
}
// Likewise a plane seen edge-on.
bool planeEdgeOn(const render::RenderView& view, const glm::dvec3& origin, const glm::dvec3& normal) {
  return std::abs(glm::dot(glm::normalize(origin - view.eye), normal)) < 0.12;
}

bool pointInPolygon(const glm::dvec2& p, const std::vector<glm::dvec2>& poly) {
  bool inside = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if (((poly[i].y > p.y) != (poly[j].y > p.y)) &&
        (p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x))
      inside = !inside;
  }
  return inside;
}

// Minimum screen distance from `pixel` to a world-space polyline; huge if
// it cannot be projected.
double distanceToPolyline(const render::RenderView& view, const std::vector<glm::dvec3>& pts, const glm::dvec2& pixel) {
  double best = 1e30;
  glm::dvec2 prev;
  bool havePrev = false;
  for (const auto& w : pts) {
    glm::dvec2 s;
    const bool ok = view.project(w, s);
    if (ok && havePrev) best = std::min(best, distanceToSegment(pixel, prev, s));
    prev = s;
    havePrev = ok;
  }
  return best;
}

std::vector<glm::dvec3> ring(const glm::dvec3& c, const glm::dvec3& u, const glm::dvec3& v, double r) {
  std::vector<glm::dvec3> pts;
  pts.reserve(kRingSegments + 1);
  for (int i = 0; i <= kRingSegments; ++i) {
    const double a = 2.0 * M_PI * i / kRingSegments;
    pts.push_back(c + (u * std::cos(a) + v * std::sin(a)) * r);
  }
  return pts;
}

void cube(render::Overlay& o, const glm::dvec3& c, const glm::dmat3& axes, double h, const glm::vec4& col) {
  glm::dvec3 p[8];
  for (int i = 0; i < 8; ++i)
    p[i] = c + axes[0] * ((i & 1) ? h : -h) + axes[1] * ((i & 2) ? h : -h) + axes[2] * ((i & 4) ? h : -h);
  const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    o.triangle(p[f[0]], p[f[1]], p[f[2]], col);
    o.triangle(p[f[0]], p[f[2]], p[f[3]], col);
  }
}

void cone(render::Overlay& o, const glm::dvec3& base, const glm::dvec3& tip, const glm::dvec3& u, const glm::dvec3& v,
          double r, const glm::vec4& col) {
  constexpr int n = 12;
  for (int i = 0; i < n; ++i) {
    const double a0 = 2.0 * M_PI * i / n, a1 = 2.0 * M_PI * (i + 1) / n;
    const glm::dvec3 p0 = base + (u * std::cos(a0) + v * std::sin(a0)) * r;
    const glm::dvec3 p1 = base + (u * std::cos(a1) + v * std::sin(a1)) * r;
    o.triangle(p0, p1, tip, col);
    o.triangle(p0, p1, base, col);
  }
}

// GL lines are one pixel wide in a core profile: shafts and rings are thin
// camera-facing quads instead, `pixels` wide.
void thickLine(render::Overlay& o, const render::RenderView& view, const glm::dvec3& a, const glm::dvec3& b,
               double pixels, const glm::vec4& col) {
  const glm::dvec3 mid = (a + b) * 0.5;
  glm::dvec3 side = glm::cross(b - a, mid - view.eye);
  const double len = glm::length(side);
  if (len < 1e-12) return o.line(a, b, col);
  const double depth = std::max(glm::dot(mid - view.eye, view.forward()), view.nearClip);
  side *= 0.5 * pixels * view.pixelSizeAt(depth) / len;
  o.triangle(a - side, b - side, b + side, col);
  o.triangle(a - side, b + side, a + side, col);
}

constexpr double kShaftPixels = 3.0, kRingPixels = 2.5;

std::atomic<int> dragCounter{0};

}  // namespace

bool Gizmo::frame(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
                  const render::RenderView& view, GizmoFrame& out) const {
  if (mode_ == GizmoMode::Select) return false;
  const std::vector<scene::EntityId> top = scene::ops::topMost(state, selection);
  if (top.empty()) return false;
  glm::dvec3 sum(0.0);
  for (scene::EntityId id : top) sum += glm::dvec3(state.worldMatrix(id)[3]);
  out.origin = sum / double(top.size());
  out.axes = glm::dmat3(1.0);
  // Scale always works along the entities' own axes (as in Unreal): a
  // world-axis scale of a rotated entity would need shear.
  if (space_ == GizmoSpace::Local || mode_ == GizmoMode::Scale) {
    const scene::EntityId primary = selection.back();
    const scene::EntityId frameOf = state.find(primary) ? primary : top.back();
    const scene::Transform w = scene::Transform::fromMatrix(state.worldMatrix(frameOf));
    out.axes = glm::mat3_cast(w.rotation);
    if (w.scale.x < 0) out.axes[0] = -out.axes[0];  // mirrored: keep handles on the visible side
  }
  const double depth = glm::dot(out.origin - view.eye, view.forward());
  if (depth <= view.nearClip) return false;
  out.length = view.pixelSizeAt(depth) * kSizePixels;
  return true;
}

void Gizmo::draw(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
                 const render::RenderView& view, render::Overlay& o) const {
  GizmoFrame f;
  if (!frame(state, selection, view, f)) return;
  const GizmoHandle lit = drag_.active ? drag_.handle : hover_;
  auto color = [&](GizmoHandle h, const glm::vec3& base, float alpha) {
    return overlayColor(h == lit ? kHoverColor : base, alpha, state.settings);
  };
  const glm::dvec3& c = f.origin;
  const double L = f.length;

  if (mode_ == GizmoMode::Translate || mode_ == GizmoMode::Scale) {
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3 a = f.axes[i], u = f.axes[(i + 1) % 3], v = f.axes[(i + 2) % 3];
      const float alpha = axisEndOn(view, c, a) ? 0.25f : 1.0f;
      const glm::vec4 col = color(axisHandle(i), kAxisColors[i], alpha);
      if (mode_ == GizmoMode::Translate) {
        thickLine(o, view, c + a * (kShaftStart * L), c + a * (kShaftEnd * L), kShaftPixels, col);
        cone(o, c + a * (kShaftEnd * L), c + a * (kTipEnd * L), u, v, kTipRadius * L, col);
        // Plane square between this axis and the next.
        int pa, pb;
        planeAxes(planeHandle(i), pa, pb);
        const glm::dvec3 n = f.axes[(i + 2) % 3];
        const float pAlpha = planeEdgeOn(view, c, n) ? 0.0f : (planeHandle(i) == lit ? 0.7f : 0.35f);
        if (pAlpha > 0.0f) {
          const glm::vec3 mixed = (kAxisColors[pa] + kAxisColors[pb]) * 0.5f;
          const glm::vec4 pc = color(planeHandle(i), mixed, pAlpha);
          const glm::dvec3 A = f.axes[pa], B = f.axes[pb];
          const glm::dvec3 q0 = c + (A * kPlaneLo + B * kPlaneLo) * L, q1 = c + (A * kPlaneHi + B * kPlaneLo) * L,
                           q2 = c + (A * kPlaneHi + B * kPlaneHi) * L, q3 = c + (A * kPlaneLo + B * kPlaneHi) * L;
          o.triangle(q0, q1, q2, pc);
          o.triangle(q0, q2, q3, pc);
          const glm::vec4 edge = color(planeHandle(i), mixed, std::min(1.0f, pAlpha + 0.4f));
          o.line(q0, q1, edge);
          o.line(q1, q2, edge);
          o.line(q2, q3, edge);
          o.line(q3, q0, edge);
        }
      } else {
        thickLine(o, view, c + a * (kShaftStart * L), c + a * (kShaftEnd * L), kShaftPixels, col);
        cube(o, c + a * (kShaftEnd * L), f.axes, kScaleCube * L, col);
      }
    }
    const glm::vec4 vc = color(GizmoHandle::View, kViewColor, 0.9f);
    if (mode_ == GizmoMode::Translate) {
      const glm::dvec3 r = view.right() * (kViewHalf * L), u = view.up() * (kViewHalf * L);
      thickLine(o, view, c - r - u, c + r - u, 2.0, vc);
      thickLine(o, view, c + r - u, c + r + u, 2.0, vc);
      thickLine(o, view, c + r + u, c - r + u, 2.0, vc);
      thickLine(o, view, c - r + u, c - r - u, 2.0, vc);
    } else {
      cube(o, c, f.axes, kUniformCube * L, vc);
    }
    return;
  }

  // Rotate: one ring per axis; the half facing away from the viewer is faint.
  const glm::dvec3 toEye = glm::normalize(view.eye - c);
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 u = f.axes[(i + 1) % 3], v = f.axes[(i + 2) % 3];
    const auto pts = ring(c, u, v, kRingRadius * L);
    const glm::vec4 front = color(axisHandle(i), kAxisColors[i], 1.0f);
    const glm::vec4 back = color(axisHandle(i), kAxisColors[i], 0.22f);
    for (size_t k = 1; k < pts.size(); ++k) {
      const glm::dvec3 mid = (pts[k - 1] + pts[k]) * 0.5;
      thickLine(o, view, pts[k - 1], pts[k], kRingPixels, glm::dot(mid - c, toEye) >= -0.02 * L ? front : back);
    }
  }
  const auto outer = ring(c, view.right(), view.up(), kViewRingRadius * L);
  const glm::vec4 vc = color(GizmoHandle::View, kViewColor, 0.8f);
  for (size_t k = 1; k < outer.size(); ++k) thickLine(o, view, outer[k - 1], outer[k], 1.5, vc);
}

GizmoHandle Gizmo::hitTest(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
                           const render::RenderView& view, const glm::dvec2& pixel) const {
  GizmoFrame f;
  if (!frame(state, selection, view, f)) return GizmoHandle::None;
  const glm::dvec3& c = f.origin;
  const double L = f.length;
  glm::dvec2 centre;
  if (!view.project(c, centre)) return GizmoHandle::None;

  GizmoHandle best = GizmoHandle::None;
  double bestDistance = kHitPixels;
  if (mode_ == GizmoMode::Translate || mode_ == GizmoMode::Scale) {
    const double centreRadius = (mode_ == GizmoMode::Translate ? kViewHalf : kUniformCube) * kSizePixels + 3.0;
    if (glm::length(pixel - centre) <= centreRadius) return GizmoHandle::View;
    if (mode_ == GizmoMode::Translate) {
      for (int i = 0; i < 3; ++i) {
        int pa, pb;
        planeAxes(planeHandle(i), pa, pb);
        if (planeEdgeOn(view, c, f.axes[(i + 2) % 3])) continue;
        const glm::dvec3 A = f.axes[pa], B = f.axes[pb];
        std::vector<glm::dvec2> quad(4);
        bool ok = view.project(c + (A * kPlaneLo + B * kPlaneLo) * L, quad[0]) &&
                  view.project(c + (A * kPlaneHi + B * kPlaneLo) * L, quad[1]) &&
                  view.project(c + (A * kPlaneHi + B * kPlaneHi) * L, quad[2]) &&
                  view.project(c + (A * kPlaneLo + B * kPlaneHi) * L, quad[3]);
        if (ok && pointInPolygon(pixel, quad)) return planeHandle(i);
      }
    }
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3 a = f.axes[i];
      if (axisEndOn(view, c, a)) continue;
      const double end = mode_ == GizmoMode::Translate ? kTipEnd : kShaftEnd + kScaleCube;
      const double d = distanceToPolyline(view, {c + a * (kShaftStart * L), c + a * (end * L)}, pixel);
      if (d < bestDistance) {
        bestDistance = d;
        best = axisHandle(i);
      }
    }
    return best;
  }

  for (int i = 0; i < 3; ++i) {
    const double d = distanceToPolyline(view, ring(c, f.axes[(i + 1) % 3], f.axes[(i + 2) % 3], kRingRadius * L), pixel);
    if (d < bestDistance) {
      bestDistance = d;
      best = axisHandle(i);
    }
  }
  const double dv = distanceToPolyline(view, ring(c, view.right(), view.up(), kViewRingRadius * L), pixel);
  if (dv < bestDistance) best = GizmoHandle::View;
  return best;
}

bool Gizmo::axisParam(const render::RenderView& view, const glm::dvec2& pixel, const glm::dvec3& axis,
                      double& t) const {
  glm::dvec3 o, d;
  view.pixelRay(pixel.x, pixel.y, o, d);
  const glm::dvec3 w0 = drag_.frame.origin - o;
  const double b = glm::dot(axis, d);
  const double denom = 1.0 - b * b;
  if (denom < 1e-6) return false;
  t = (b * glm::dot(d, w0) - glm::dot(axis, w0)) / denom;
  return std::isfinite(t);
}

bool Gizmo::planeHit(const render::RenderView& view, const glm::dvec2& pixel, const glm::dvec3& normal,
                     glm::dvec3& hit) const {
  glm::dvec3 o, d;
  view.pixelRay(pixel.x, pixel.y, o, d);
  const double denom = glm::dot(d, normal);
  if (std::abs(denom) < 1e-6) return false;
  const double s = glm::dot(drag_.frame.origin - o, normal) / denom;
  if (s <= 0.0 || !std::isfinite(s)) return false;
  hit = o + d * s;
  return true;
}

bool Gizmo::beginDrag(const scene::SceneState& state, const std::vector<scene::EntityId>& selection,
                      const render::RenderView& view, GizmoHandle handle, const glm::dvec2& pixel) {
  drag_ = {};
  if (handle == GizmoHandle::None || !frame(state, selection, view, drag_.frame)) return false;
  drag_.handle = handle;
  drag_.mode = mode_;
  drag_.startPixel = pixel;
  if (!view.project(drag_.frame.origin, drag_.centrePixel)) return false;
  for (scene::EntityId id : scene::ops::topMost(state, selection)) {
    const scene::Entity* e = state.find(id);
    Item item{id, e->transform, state.worldMatrix(id),
              e->parent == scene::kNoEntity ? glm::dmat4(1.0) : state.worldMatrix(e->parent)};
    drag_.items.push_back(item);
  }
  if (drag_.items.empty()) return false;

  const int axis = axisIndex(handle);
  int pa, pb;
  if (mode_ == GizmoMode::Translate || mode_ == GizmoMode::Scale) {
    if (axis >= 0) {
      if (!axisParam(view, pixel, drag_.frame.axes[axis], drag_.startT)) return false;
    } else if (planeAxes(handle, pa, pb)) {
      if (!planeHit(view, pixel, glm::cross(drag_.frame.axes[pa], drag_.frame.axes[pb]), drag_.startHit)) return false;
    } else if (mode_ == GizmoMode::Translate) {
      if (!planeHit(view, pixel, view.forward(), drag_.startHit)) return false;
    }
  } else {
    drag_.lastAngle = std::atan2(pixel.y - drag_.centrePixel.y, pixel.x - drag_.centrePixel.x);
  }
  drag_.key = QString("gizmo-drag-%1").arg(++dragCounter);
  drag_.active = true;
  return true;
}

TransformList Gizmo::dragTransforms(const render::RenderView& view, const glm::dvec2& pixel, bool invertSnap) {
  TransformList out;
  if (!drag_.active) return out;
  const bool snapOn = snap_.enabled != invertSnap;
  const GizmoFrame& f = drag_.frame;
  const int axis = axisIndex(drag_.handle);
  int pa = -1, pb = -1;
  planeAxes(drag_.handle, pa, pb);

  if (drag_.mode == GizmoMode::Translate) {
    glm::dvec3 delta(0.0);
    if (axis >= 0) {
      double t;
      if (!axisParam(view, pixel, f.axes[axis], t)) return out;
      delta = f.axes[axis] * (t - drag_.startT);
    } else {
      glm::dvec3 hit;
      const glm::dvec3 n = pa >= 0 ? glm::cross(f.axes[pa], f.axes[pb]) : view.forward();
      if (!planeHit(view, pixel, n, hit)) return out;
      delta = hit - drag_.startHit;
    }
    if (snapOn && snap_.move > 0.0) {
      // World space snaps the primary's position to the grid along the moved
      // axes; local space snaps the distance moved.
      glm::dvec3 local = glm::transpose(f.axes) * delta;
      const glm::dvec3 startPos(drag_.items.back().world[3]);
      const glm::dvec3 startLocal = glm::transpose(f.axes) * startPos;
      for (int k = 0; k < 3; ++k) {
        const bool moved = axis == k || pa == k || pb == k || (axis < 0 && pa < 0);
        if (!moved) continue;
        local[k] = space_ == GizmoSpace::World && drag_.mode == GizmoMode::Translate
                       ? snapTo(startLocal[k] + local[k], snap_.move) - startLocal[k]
                       : snapTo(local[k], snap_.move);
      }
      delta = f.axes * local;
    }
    for (const Item& it : drag_.items) {
      scene::Transform t = it.local;
      t.translation = it.local.translation + glm::inverse(glm::dmat3(it.parentWorld)) * delta;
      out.emplace_back(it.id, t);
    }
    return out;
  }

  if (drag_.mode == GizmoMode::Rotate) {
    const double now = std::atan2(pixel.y - drag_.centrePixel.y, pixel.x - drag_.centrePixel.x);
    drag_.angle += wrapAngle(now - drag_.lastAngle);
    drag_.lastAngle = now;
    const glm::dvec3 rotAxis = axis >= 0 ? f.axes[axis] : -view.forward();
    // Pixel y points down: a turn that looks counter-clockwise to the viewer
    // lowers the screen angle, and is positive about an axis facing them.
    const double facing = glm::dot(rotAxis, view.eye - f.origin) >= 0.0 ? 1.0 : -1.0;
    double angle = -drag_.angle * facing;
    if (snapOn && snap_.rotateDeg > 0.0) angle = glm::radians(snapTo(glm::degrees(angle), snap_.rotateDeg));
    const glm::dmat4 r = glm::translate(glm::dmat4(1.0), f.origin) *
                         glm::mat4_cast(glm::angleAxis(angle, rotAxis)) *
                         glm::translate(glm::dmat4(1.0), -f.origin);
    for (const Item& it : drag_.items) {
      scene::Transform t = scene::Transform::fromMatrix(glm::inverse(it.parentWorld) * r * it.world);
      t.scale = it.local.scale;  // a rotation never changes scale; keep it bit-exact
      out.emplace_back(it.id, t);
    }
    return out;
  }

  if (drag_.mode == GizmoMode::Scale) {
    double factor = 1.0;
    if (axis >= 0) {
      double t;
      if (!axisParam(view, pixel, f.axes[axis], t)) return out;
      factor = std::abs(drag_.startT) > 0.05 * f.length ? t / drag_.startT : 1.0 + (t - drag_.startT) / f.length;
    } else {
      const double d0 = glm::length(drag_.startPixel - drag_.centrePixel);
      const double d1 = glm::length(pixel - drag_.centrePixel);
      factor = d0 > 3.0 ? d1 / d0 : 1.0 + (pixel.x - drag_.startPixel.x) / 100.0;
    }
    if (snapOn && snap_.scale > 0.0) factor = snapTo(factor, snap_.scale);
    factor = std::max(factor, 1e-3);
    glm::dvec3 fv(1.0);
    if (axis >= 0)
      fv[axis] = factor;
    else
      fv = glm::dvec3(factor);
    for (const Item& it : drag_.items) {
      scene::Transform t = it.local;
      t.scale = it.local.scale * fv;
      // Positions spread from the pivot along the gizmo's axes.
      const glm::dvec3 p0(it.world[3]);
      const glm::dvec3 p = f.origin + f.axes * (fv * (glm::transpose(f.axes) * (p0 - f.origin)));
      t.translation = glm::dvec3(glm::inverse(it.parentWorld) * glm::dvec4(p, 1.0));
      if (glm::length(p - p0) == 0.0) t.translation = it.local.translation;
      out.emplace_back(it.id, t);
    }
    return out;
  }
  return out;
}

bool Gizmo::dragTo(scene::Document& doc, const render::RenderView& view, const glm::dvec2& pixel, bool invertSnap) {
  const TransformList list = dragTransforms(view, pixel, invertSnap);
  if (list.empty()) return false;
  return scene::ops::setTransforms(doc, list, undoText(), drag_.key);
}

void Gizmo::cancelDrag(scene::Document& doc) {
  if (!drag_.active) return;
  TransformList list;
  for (const Item& it : drag_.items)
    if (doc.state().find(it.id)) list.emplace_back(it.id, it.local);
  scene::ops::setTransforms(doc, list, undoText(), drag_.key);
  endDrag();
}

QString Gizmo::undoText() const {
  const size_t n = drag_.items.size();
  const QString what = n == 1 ? QString() : QString(" %1 entities").arg(n);
  switch (drag_.mode) {
    case GizmoMode::Translate: return "Move" + what;
    case GizmoMode::Rotate: return "Rotate" + what;
    case GizmoMode::Scale: return "Scale" + what;
    default: return "Transform" + what;
  }
}

}  // namespace hs::app

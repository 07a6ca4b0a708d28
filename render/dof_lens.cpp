#include "render/dof_lens.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "scene/components.h"

namespace hs::render {

double DofLens::cocPixels(double z) const {
  if (!valid) return 0.0;
  const double invZ = std::isfinite(z) && z > 0.0 ? 1.0 / z : 0.0;
  return cocScale * (1.0 / focusDistance - invZ);
}

DofLens dofLensOf(const RenderView& view) {
  DofLens out;
  const CameraLens& l = view.lens;
  if (!l.present) return out;
  const std::string who = "camera '" + l.camera + "': ";
  if (!std::isfinite(l.fStop) || l.fStop <= 0.0) {
    out.problem = who + "f_stop: " + std::to_string(l.fStop) + " is not a positive number; depth of field left out";
    return out;
  }
  if (!std::isfinite(l.focusDistance) || l.focusDistance <= 0.0) {
    out.problem =
        who + "focus_distance_m: " + std::to_string(l.focusDistance) + " is not a positive distance; depth of field left out";
    return out;
  }
  const double tanHalf = std::tan(view.fovY * 0.5);
  out.valid = true;
  out.focusDistance = l.focusDistance;
  out.focalLength = scene::kSensorHeightMm * 1e-3 / (2.0 * tanHalf);
  out.aperture = out.focalLength / l.fStop;
  out.cocScale = out.aperture * double(view.height) / (2.0 * tanHalf);
  return out;
}

double maxCocPixels(const DofLens& lens, double zNear) {
  if (!lens.valid) return 0.0;
  return std::max(std::abs(lens.cocPixels(std::max(zNear, 1e-9))), std::abs(lens.cocPixels(INFINITY)));
}

std::vector<glm::dvec2> lensDiscSamples(int n, uint32_t seed) {
  // std::mt19937's sequence is fixed by the standard; the conversion to
  // [0, 1) is done here (the distributions' are not).
  std::mt19937 rng(seed);
  const auto unit = [&] { return double(rng() >> 8) / double(1u << 24); };
  std::vector<glm::dvec2> out;
  out.reserve(size_t(std::max(n, 0)));
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    // Radius from the stratum's share of the area, angle by the golden
    // angle; both jittered within the stratum.
    const double r = std::sqrt((double(i) + unit()) / double(n));
    const double a = (double(i) + 0.5 * (unit() - 0.5)) * golden;
    out.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return out;
}

RenderView lensSampleView(const RenderView& view, const DofLens& lens, glm::dvec2 disc) {
  RenderView v = view;
  const glm::dvec2 d = disc * (lens.aperture * 0.5);  // metres on the lens, camera axes
  v.eye = view.eye + view.right() * d.x + view.up() * d.y;
  // A focus-plane point keeps its NDC: shift by the offset seen at distance s.
  const double tanHalf = std::tan(view.fovY * 0.5);
  v.projectionShift.x += d.x / (lens.focusDistance * tanHalf * view.aspect());
  v.projectionShift.y += d.y / (lens.focusDistance * tanHalf);
  return v;
}

}  // namespace hs::render

#include "sequencer/comfort_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hs::sequencer {

double linearDepthFromReversedZ(double d, double n, double f) {
  if (!(d > 0.0)) return std::numeric_limits<double>::infinity();
  return n * f / (d * (f - n) + n);
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double depthAt(const DepthImage& img, size_t i) {
  const double d = img.depth[i];
  if (img.kind == DepthKind::ReversedZ) return linearDepthFromReversedZ(d, img.nearClip, img.farClip);
  return (d > 0.0 && std::isfinite(d)) ? d : kInf;
}

void include(ComfortResult& r, double parallax, double depth) {
  if (!std::isfinite(parallax)) return;
  if (!r.hasPixels) {
    r.nearestParallax = r.farthestParallax = parallax;
    r.hasPixels = true;
  }
  r.nearestParallax = std::min(r.nearestParallax, parallax);
  r.farthestParallax = std::max(r.farthestParallax, parallax);
  r.nearestDepth = std::min(r.nearestDepth, depth);
  r.farthestDepth = std::max(r.farthestDepth, depth);
}

// Reprojection of every pixel of `from` into `to` (toe-in rigs).
void reproject(ComfortResult& r, const CameraModel& from, const CameraModel& to, const DepthImage& img,
               bool fromIsLeft, const ComfortOptions& o) {
  const int stride = std::max(1, o.stride);
  for (int y = 0; y < img.height; y += stride)
    for (int x = 0; x < img.width; x += stride) {
      const double z = depthAt(img, size_t(y) * size_t(img.width) + size_t(x));
      if (std::isinf(z) && !o.skyAtInfinity) continue;
      const glm::dvec2 ndc(2.0 * (x + 0.5) / img.width - 1.0, 1.0 - 2.0 * (y + 0.5) / img.height);
      std::optional<glm::dvec2> other;
      if (std::isinf(z)) {
        const glm::dvec3 dir = from.unproject(ndc, 1.0) - from.position;
        other = to.projectDirectionNdc(dir);
      } else {
        other = to.projectNdc(from.unproject(ndc, z));
      }
      if (!other) continue;
      const double p = 0.5 * (fromIsLeft ? other->x - ndc.x : ndc.x - other->x);
      include(r, p, z);
    }
}

void depthRange(const DepthImage& img, const ComfortOptions& o, double& lo, double& hi, bool& any) {
  const int stride = std::max(1, o.stride);
  for (int y = 0; y < img.height; y += stride)
    for (int x = 0; x < img.width; x += stride) {
      const double z = depthAt(img, size_t(y) * size_t(img.width) + size_t(x));
      if (std::isinf(z) && !o.skyAtInfinity) continue;
      lo = std::min(lo, z);
      hi = std::max(hi, z);
      any = true;
    }
}

}  // namespace

ComfortResult checkComfort(const StereoCameras& eyes, const DepthImage& left, const DepthImage* right,
                           const ComfortOptions& o) {
  ComfortResult r;
  const bool toeIn = eyes.mode == StereoMode::ToeIn;
  if (toeIn) {
    if (left.depth) reproject(r, eyes.left, eyes.right, left, true, o);
    if (right && right->depth) reproject(r, eyes.right, eyes.left, *right, false, o);
  } else {
    double lo = kInf, hi = 0.0;
    bool any = false;
    if (left.depth) depthRange(left, o, lo, hi, any);
    if (right && right->depth) depthRange(*right, o, lo, hi, any);
    if (any) {
      // Parallax grows with depth: the nearest point has the smallest.
      include(r, midlineParallax(eyes, lo), lo);
      include(r, midlineParallax(eyes, hi), hi);
    }
  }
  if (r.hasPixels && (r.nearestParallax < o.budget.nearest || r.farthestParallax > o.budget.farthest)) {
    r.withinBudget = false;
    char msg[256];
    if (r.nearestParallax < o.budget.nearest) {
      std::snprintf(msg, sizeof msg, "nearest parallax %.2f%% at %.2f m is beyond the budget's %.2f%%",
                    r.nearestParallax * 100.0, r.nearestDepth, o.budget.nearest * 100.0);
      r.message = msg;
    }
    if (r.farthestParallax > o.budget.farthest) {
      const std::string where = std::isinf(r.farthestDepth) ? "infinity" : std::to_string(r.farthestDepth) + " m";
      std::snprintf(msg, sizeof msg, "farthest parallax %.2f%% at %s is beyond the budget's +%.2f%%",
                    r.farthestParallax * 100.0, where.c_str(), o.budget.farthest * 100.0);
      r.message += (r.message.empty() ? "" : "; ") + std::string(msg);
    }
  }
  return r;
}

std::vector<int64_t> framesOutsideBudget(const std::vector<FrameComfort>& frames) {
  std::vector<int64_t> out;
  for (const FrameComfort& f : frames)
    if (!f.result.withinBudget) out.push_back(f.frame);
  return out;
}

std::optional<StereoRig> suggestRig(double zn, double zf, double tanHalfX, const ComfortBudget& budget) {
  if (!(zn > 0.0) || !(zf > zn) || !(tanHalfX > 0.0) || !(budget.farthest > budget.nearest)) return std::nullopt;
  const double invFar = std::isinf(zf) ? 0.0 : 1.0 / zf;
  StereoRig rig;
  rig.interaxial = 2.0 * tanHalfX * (budget.farthest - budget.nearest) / (1.0 / zn - invFar);
  const double invC = 2.0 * tanHalfX * budget.farthest / rig.interaxial + invFar;
  rig.convergence = invC > 0.0 ? 1.0 / invC : std::numeric_limits<double>::infinity();
  return rig;
}

}  // namespace hs::sequencer

#include "sequencer/stereo_rig.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace hs::sequencer {

const char* stereoModeName(StereoMode m) {
  switch (m) {
    case StereoMode::OffAxis: return "off_axis";
    case StereoMode::Parallel: return "parallel";
    case StereoMode::ToeIn: return "toe_in";
  }
  return "?";
}

const char* rigPivotName(RigPivot p) {
  switch (p) {
    case RigPivot::Left: return "left";
    case RigPivot::Centre: return "centre";
    case RigPivot::Right: return "right";
  }
  return "?";
}

std::optional<RigPivot> rigPivotFromName(std::string_view s) {
  for (auto p : {RigPivot::Left, RigPivot::Centre, RigPivot::Right})
    if (s == rigPivotName(p)) return p;
  if (s == "center") return RigPivot::Centre;
  return std::nullopt;
}

glm::dmat4 CameraModel::projection() const {
  const double f = 1.0 / std::tan(fovY * 0.5);
  const double n = nearClip, fa = std::max(farClip, nearClip * 1.0001);
  glm::dmat4 p(0.0);
  p[0][0] = f / aspect;
  p[1][1] = f;
  p[2][0] = -ndcShiftX;  // x_clip -= shift * z_view, w = -z_view: ndc.x += shift
  p[2][2] = n / (fa - n);
  p[2][3] = -1.0;
  p[3][2] = n * fa / (fa - n);
  return p;
}

glm::dmat4 CameraModel::view() const {
  glm::dmat4 v(glm::mat3_cast(glm::conjugate(orientation)));
  v[3] = glm::dvec4(-(glm::dmat3(v) * position), 1.0);
  return v;
}

namespace {
std::optional<glm::dvec2> ndcOfView(const CameraModel& c, const glm::dvec3& v) {
  if (v.z >= 0.0) return std::nullopt;
  const double f = 1.0 / std::tan(c.fovY * 0.5);
  return glm::dvec2(f / c.aspect * v.x / -v.z + c.ndcShiftX, f * v.y / -v.z);
}
}  // namespace

std::optional<glm::dvec2> CameraModel::projectNdc(const glm::dvec3& world) const {
  return ndcOfView(*this, glm::conjugate(orientation) * (world - position));
}

std::optional<glm::dvec2> CameraModel::projectDirectionNdc(const glm::dvec3& dir) const {
  return ndcOfView(*this, glm::conjugate(orientation) * dir);
}

std::optional<glm::dvec2> CameraModel::projectPixel(const glm::dvec3& world, int width, int height) const {
  const auto ndc = projectNdc(world);
  if (!ndc) return std::nullopt;
  return glm::dvec2((ndc->x + 1.0) * 0.5 * width, (1.0 - ndc->y) * 0.5 * height);
}

glm::dvec3 CameraModel::unproject(const glm::dvec2& ndc, double depth) const {
  const double t = std::tan(fovY * 0.5);
  const glm::dvec3 v((ndc.x - ndcShiftX) * t * aspect * depth, ndc.y * t * depth, -depth);
  return position + orientation * v;
}

StereoCameras stereoCameras(const CameraModel& mono, const StereoRig& rig) {
  StereoCameras out;
  out.left = out.right = mono;
  out.mode = rig.mode;
  const double b = rig.interaxial;
  if (b < 0.0) out.warnings.push_back("negative interaxial: the eyes are swapped (pseudo-stereo)");
  double leftOffset = -0.5 * b, rightOffset = 0.5 * b;  // along the mono camera's right axis
  if (rig.pivot == RigPivot::Left) leftOffset = 0.0, rightOffset = b;
  if (rig.pivot == RigPivot::Right) leftOffset = -b, rightOffset = 0.0;
  const glm::dvec3 right = mono.right();
  out.left.position = mono.position + right * leftOffset;
  out.right.position = mono.position + right * rightOffset;
  if (b == 0.0) return out;  // one viewpoint: identical eyes whatever the mode

  const double c = rig.convergence;
  if (rig.mode != StereoMode::Parallel && !(c > 0.0 && std::isfinite(c))) {
    out.warnings.push_back("convergence distance must be positive; using parallel eyes");
    return out;
  }
  if (rig.mode != StereoMode::Parallel && c < mono.nearClip)
    out.warnings.push_back("the convergence plane is nearer than the near clip plane: everything is behind the screen");

  const double tanHalfX = std::tan(mono.fovY * 0.5) * mono.aspect;
  if (rig.mode == StereoMode::OffAxis) {
    const double shift = 0.5 * b / (c * tanHalfX);
    out.left.ndcShiftX = mono.ndcShiftX - shift;
    out.right.ndcShiftX = mono.ndcShiftX + shift;
  } else if (rig.mode == StereoMode::ToeIn) {
    const double angle = std::atan(0.5 * b / c);
    // Yaw inward about the camera's own up axis: the left eye turns right
    // (a negative turn about +Y), the right eye turns left.
    out.left.orientation = glm::normalize(mono.orientation * glm::angleAxis(-angle, glm::dvec3(0, 1, 0)));
    out.right.orientation = glm::normalize(mono.orientation * glm::angleAxis(angle, glm::dvec3(0, 1, 0)));
    // Size of the keystone: vertical disparity of the convergence window's corners.
    const double tanY = std::tan(mono.fovY * 0.5);
    const glm::dvec3 centre = mono.position + right * (0.5 * (leftOffset + rightOffset));
    double worst = 0.0;
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0}) {
        const glm::dvec3 corner = centre + mono.orientation * glm::dvec3(sx * tanHalfX * c, sy * tanY * c, -c);
        const auto l = out.left.projectNdc(corner), r = out.right.projectNdc(corner);
        if (l && r) worst = std::max(worst, std::abs(l->y - r->y) * 0.5);
      }
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "toe-in rig: vertical parallax up to %.2f%% of the image height at the corners (keystone), "
                  "which strains the eyes; prefer off-axis",
                  worst * 100.0);
    out.warnings.push_back(msg);
  }
  return out;
}

double midlineParallax(const StereoCameras& eyes, double depth) {
  const glm::dvec3 centre = 0.5 * (eyes.left.position + eyes.right.position);
  // The mono axis: the eyes' mean forward direction.
  const glm::dvec3 fwd = glm::normalize(eyes.left.forward() + eyes.right.forward());
  std::optional<glm::dvec2> l, r;
  if (std::isinf(depth)) {
    l = eyes.left.projectDirectionNdc(fwd);
    r = eyes.right.projectDirectionNdc(fwd);
  } else {
    const glm::dvec3 p = centre + fwd * depth;
    l = eyes.left.projectNdc(p);
    r = eyes.right.projectNdc(p);
  }
  if (!l || !r) return std::numeric_limits<double>::quiet_NaN();
  return 0.5 * (r->x - l->x);
}

}  // namespace hs::sequencer

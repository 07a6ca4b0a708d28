#include "render/local_shadows.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

namespace hs::render {
namespace {

void addProblem(std::string* problem, const std::string& text) {
  if (!problem) return;
  if (!problem->empty()) *problem += "; ";
  *problem += text;
}

// Reversed, infinite-far perspective: clip (x / t, y / t, near, d) for a
// point d metres along the axis, so depth = near / d (1 at the near plane).
glm::dmat4 reversedPerspective(double tanHalf, double nearPlane) {
  glm::dmat4 p(0.0);
  p[0][0] = 1.0 / tanHalf;
  p[1][1] = 1.0 / tanHalf;
  p[3][2] = nearPlane;
  p[2][3] = -1.0;
  return p;
}

LocalShadowFace face(const glm::dvec3& position, const glm::dvec3& axis, double tanHalf, double nearPlane) {
  LocalShadowFace f;
  f.axis = axis;
  // The up vector is fixed in the world (as the sun's), so a turning spot
  // never rolls its map.
  const glm::dvec3 up = std::abs(axis.z) < 0.99 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  const glm::dmat4 toView = glm::lookAt(position, position + axis, up);
  f.frameToClip = reversedPerspective(tanHalf, nearPlane) * toView;
  glm::dmat4 bias(1.0);
  bias[0][0] = bias[1][1] = 0.5;
  bias[3][0] = bias[3][1] = 0.5;  // times w: (x / w) * 0.5 + 0.5 after the divide
  f.frameToMap = bias * f.frameToClip;
  return f;
}

}  // namespace

int localShadowResolution(const WorldLight& light, const std::string& name, const ShadowConfig& config,
                          int maxTextureSize, std::string* problem) {
  const bool cube = light.type == scene::Light::Type::Point ||
                    std::acos(double(light.cosOuterHalf)) * 2.0 > glm::radians(kSpotAsCubeDeg);
  int r = light.shadowResolution;
  if (r == 0) {
    r = cube ? std::max(config.resolution / 2, kMinLocalShadowResolution) : config.resolution;
  } else if (r < kMinLocalShadowResolution || r > kMaxLocalShadowResolution) {
    const int c = std::clamp(r, kMinLocalShadowResolution, kMaxLocalShadowResolution);
    std::ostringstream s;
    s << "light '" << name << "': shadow_resolution: " << r << " is out of range (" << kMinLocalShadowResolution
      << " to " << kMaxLocalShadowResolution << "; 0: from the settings), using " << c;
    addProblem(problem, s.str());
    r = c;
  }
  if (maxTextureSize > 0 && r > maxTextureSize) {
    addProblem(problem, "light '" + name + "': shadow_resolution: " + std::to_string(r) +
                            " is larger than this GPU allows, using " + std::to_string(maxTextureSize));
    r = maxTextureSize;
  }
  return r;
}

bool lightReachesViews(const WorldLight& light, const std::vector<RenderView>& views) {
  if (!(light.range > 0.0f)) return false;
  for (const RenderView& v : views)
    if (frustumOf(v).intersectsSphere(light.position - v.eye, double(light.range))) return true;
  return false;
}

LocalShadow computeLocalShadow(const WorldLight& light, size_t index, int resolution, int pcfRadius,
                               const glm::dvec3& frameOrigin) {
  LocalShadow s;
  s.light = index;
  s.resolution = resolution;
  s.range = double(light.range);
  s.position = light.position - frameOrigin;
  // 5 cm, or a tenth of a short range: casters nearer the light than this
  // are clipped (nothing sits inside a lamp).
  s.nearPlane = std::min(0.05, 0.1 * s.range);
  // Guard band: the kernel's taps around any point the face serves stay
  // inside the map (the kernel's radius, the bilinear tap and one for the
  // normal offset's reach).
  const double guard = double(pcfRadius) + 2.0;
  const double widen = double(resolution) / std::max(double(resolution) - 2.0 * guard, 1.0);
  const double outerHalf = std::acos(std::clamp(double(light.cosOuterHalf), -1.0, 1.0));
  const bool cube = light.type == scene::Light::Type::Point || outerHalf * 2.0 > glm::radians(kSpotAsCubeDeg);
  if (cube) {
    s.tanHalfFov = widen;  // 45 degrees and the guard band
    for (int a = 0; a < 3; ++a)
      for (double sign : {1.0, -1.0}) {
        glm::dvec3 axis(0.0);
        axis[a] = sign;
        s.faces.push_back(face(s.position, axis, s.tanHalfFov, s.nearPlane));
      }
  } else {
    s.tanHalfFov = std::tan(outerHalf) * widen;
    s.faces.push_back(face(s.position, glm::normalize(light.direction), s.tanHalfFov, s.nearPlane));
  }
  return s;
}

Frustum localShadowVolume(const LocalShadow& shadow, const LocalShadowFace& f) {
  const glm::dmat4& m = f.frameToClip;
  auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  Frustum out;
  out.planes[0] = row(3) + row(0);
  out.planes[1] = row(3) - row(0);
  out.planes[2] = row(3) + row(1);
  out.planes[3] = row(3) - row(1);
  out.planes[4] = row(3) - row(2);  // beyond the near plane
  // Within the range along the axis: dot(axis, p - position) <= range.
  out.planes[5] = glm::dvec4(-f.axis, glm::dot(f.axis, shadow.position) + shadow.range);
  for (glm::dvec4& p : out.planes) p /= glm::length(glm::dvec3(p));
  return out;
}

}  // namespace hs::render

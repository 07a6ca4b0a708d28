#include "render/shadow_cascades.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace hs::render {
namespace {

struct Preset {
  int resolution, cascades, pcfRadius;
};
// Low: one 1k map per near/far half; high: 4k maps, 4 cascades, 5x5 PCF.
constexpr Preset kPresets[3] = {{1024, 2, 1}, {2048, 3, 1}, {4096, 4, 2}};

int clampField(int v, int lo, int hi, const char* key, std::string* problem) {
  if (v >= lo && v <= hi) return v;
  const int c = std::clamp(v, lo, hi);
  if (problem) {
    std::ostringstream s;
    s << "settings." << key << ": " << v << " is out of range (" << lo << " to " << hi << "), using " << c;
    if (!problem->empty()) *problem += "; ";
    *problem += s.str();
  }
  return c;
}

}  // namespace

ShadowConfig resolveShadowConfig(const scene::SceneSettings& s, int maxTextureSize, std::string* problem) {
  ShadowConfig c;
  c.enabled = s.shadows;
  if (s.shadowQuality == scene::ShadowQuality::Custom) {
    c.resolution = clampField(s.shadowResolution, 256, 8192, "shadow_resolution", problem);
    c.cascades = clampField(s.shadowCascades, 1, kMaxShadowCascades, "shadow_cascades", problem);
    c.pcfRadius = clampField(s.shadowPcfRadius, 0, 3, "shadow_pcf", problem);
  } else {
    const Preset& p = kPresets[std::clamp(int(s.shadowQuality), 0, 2)];
    c.resolution = p.resolution;
    c.cascades = p.cascades;
    c.pcfRadius = p.pcfRadius;
  }
  if (maxTextureSize > 0 && c.resolution > maxTextureSize) {
    if (problem) {
      if (!problem->empty()) *problem += "; ";
      *problem += "settings.shadow_resolution: " + std::to_string(c.resolution) + " is larger than this GPU allows, using " +
                  std::to_string(maxTextureSize);
    }
    c.resolution = maxTextureSize;
  }
  c.distance = std::isfinite(s.shadowDistance) ? std::clamp(s.shadowDistance, 1.0, 100000.0) : 30000.0;
  return c;
}

std::vector<double> cascadeSplits(double nearClip, double farClip, int cascades) {
  std::vector<double> out{nearClip};
  const double logNear = std::max(nearClip, kShadowMinSplitNear);
  for (int i = 1; i < cascades; ++i) {
    const double f = double(i) / double(cascades);
    const double logSplit = logNear < farClip ? logNear * std::pow(farClip / logNear, f) : farClip;
    const double uniform = nearClip + (farClip - nearClip) * f;
    out.push_back(kShadowSplitLambda * logSplit + (1.0 - kShadowSplitLambda) * uniform);
  }
  out.push_back(farClip);
  return out;
}

SunCascades computeSunCascades(const RenderView& view, const glm::dvec3& sunDirection, const ShadowConfig& config,
                               const glm::dvec3& frameOrigin) {
  SunCascades out;
  out.frameOrigin = frameOrigin;
  // Light space: z towards the sun, x and y across the map. The up vector
  // is fixed in the world (not the camera's), so turning the camera never
  // turns the map.
  const glm::dvec3 z = -glm::normalize(sunDirection);
  const glm::dvec3 ref = std::abs(z.z) < 0.99 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  const glm::dvec3 x = glm::normalize(glm::cross(ref, z));
  const glm::dvec3 y = glm::cross(z, x);
  // Rows x, y, z: world -> light.
  out.lightRotation = glm::transpose(glm::dmat3(x, y, z));

  out.anchor = glm::round(view.eye / kShadowAnchorLattice) * kShadowAnchorLattice;
  const double farClip = std::min(view.farClip, config.distance);
  const double nearClip = std::min(view.nearClip, farClip * 0.5);
  const std::vector<double> splits = cascadeSplits(nearClip, farClip, config.cascades);
  const double ty = std::tan(view.fovY * 0.5), tx = ty * view.aspect();
  const double k = tx * tx + ty * ty;
  const glm::dvec3 forward = view.forward();
  for (int i = 0; i < config.cascades; ++i) {
    ShadowCascade c;
    const double n = splits[size_t(i)], f = splits[size_t(i) + 1];
    c.splitNear = n;
    c.splitFar = f;
    // The smallest sphere around the slice's eight corners, centred on the
    // view axis at depth d: corners at depth n and f equally far, unless
    // that puts d beyond f. Depends on fov, aspect, n and f only.
    const double d = std::min((1.0 + k) * (f + n) * 0.5, f);
    double r = std::sqrt(std::max(k * f * f + (f - d) * (f - d), k * n * n + (n - d) * (n - d)));
    // Rounded up to 1/64 of its power of two: the same size as the split
    // moves by rounding errors of a frame.
    const double quantum = std::exp2(std::ceil(std::log2(r))) / 64.0;
    r = std::ceil(r / quantum) * quantum;
    c.radius = r;
    c.texelMetres = 2.0 * r / double(config.resolution);
    // In double, relative to the anchor: the snapped centre is the same for
    // every camera position that maps to the same texel.
    const glm::dvec3 centreLight = out.lightRotation * (view.eye + forward * d - out.anchor);
    c.centreLight = glm::floor(centreLight / c.texelMetres) * c.texelMetres;
    // Frame-relative p -> light: R p + (R (origin - anchor) - centre).
    const glm::dvec3 t = out.lightRotation * (frameOrigin - out.anchor) - c.centreLight;
    glm::dmat4 toLight(out.lightRotation);
    toLight[3] = glm::dvec4(t, 1.0);
    // Orthographic: x, y over [-r, r] -> [-1, 1]; z from -r (1 r below the
    // centre, away from the sun) to +r (the sun's side) -> depth 0..1.
    // Casters beyond +r (towards the sun) are clamped onto it (depth clamp)
    // and still shadow what lies inside.
    glm::dmat4 ortho(1.0);
    ortho[0][0] = 1.0 / r;
    ortho[1][1] = 1.0 / r;
    ortho[2][2] = 0.5 / r;
    ortho[3][2] = 0.5;
    c.frameToClip = ortho * toLight;
    glm::dmat4 bias(1.0);
    bias[0][0] = bias[1][1] = 0.5;
    bias[3][0] = bias[3][1] = 0.5;
    c.frameToMap = bias * c.frameToClip;
    out.cascades.push_back(c);
  }
  return out;
}

}  // namespace hs::render

#include "render/impostor_atlas.h"

#include <algorithm>
#include <cmath>

namespace hs::render {

glm::dvec2 hemiOctEncode(const glm::dvec3& dIn) {
  glm::dvec3 d(dIn.x, dIn.y, std::max(dIn.z, 0.0));
  const double sum = std::abs(d.x) + std::abs(d.y) + d.z;
  if (!(sum > 0.0)) return {0.5, 0.5};
  d /= sum;
  return glm::clamp(glm::dvec2(d.x + d.y, d.x - d.y) * 0.5 + 0.5, 0.0, 1.0);
}

glm::dvec3 hemiOctDecode(const glm::dvec2& g) {
  const glm::dvec2 e = glm::clamp(g, 0.0, 1.0) * 2.0 - 1.0;
  glm::dvec3 d(0.5 * (e.x + e.y), 0.5 * (e.x - e.y), 0.0);
  d.z = std::max(0.0, 1.0 - std::abs(d.x) - std::abs(d.y));
  return glm::normalize(d);
}

glm::dvec3 impostorFrameDirection(int i, int j) {
  return hemiOctDecode(glm::dvec2(i, j) / double(kImpostorFrames - 1));
}

ImpostorBasis impostorBasis(const glm::dvec3& d) {
  glm::dvec3 right(-d.y, d.x, 0.0);  // z x d
  const double len = glm::length(right);
  right = len > 1e-6 ? right / len : glm::dvec3(1.0, 0.0, 0.0);
  return {right, glm::normalize(glm::cross(d, right))};
}

ImpostorBlend impostorBlend(const glm::dvec3& d) {
  const glm::dvec2 g = hemiOctEncode(d) * double(kImpostorFrames - 1);
  const glm::ivec2 base = glm::clamp(glm::ivec2(glm::floor(g)), 0, kImpostorFrames - 2);
  const glm::dvec2 f = glm::clamp(g - glm::dvec2(base), 0.0, 1.0);
  ImpostorBlend b;
  if (f.x + f.y <= 1.0) {
    b.frames = {base, base + glm::ivec2(1, 0), base + glm::ivec2(0, 1)};
    b.weights = {1.0 - f.x - f.y, f.x, f.y};
  } else {
    b.frames = {base + glm::ivec2(1, 1), base + glm::ivec2(0, 1), base + glm::ivec2(1, 0)};
    b.weights = {f.x + f.y - 1.0, 1.0 - f.x, 1.0 - f.y};
  }
  return b;
}

double impostorCoveringAngle() {
  static const double angle = [] {
    // The farthest point of a grid cell from its nearest corner lies inside
    // the cell: sample every cell finely and take the worst.
    constexpr int kSamples = 24;
    double worst = 0.0;
    const int n = kImpostorFrames - 1;
    for (int ci = 0; ci < n; ++ci)
      for (int cj = 0; cj < n; ++cj)
        for (int a = 0; a <= kSamples; ++a)
          for (int b = 0; b <= kSamples; ++b) {
            const glm::dvec3 d = hemiOctDecode((glm::dvec2(ci, cj) + glm::dvec2(a, b) / double(kSamples)) / double(n));
            double best = 0.0;  // the largest cosine over the cell's corners
            for (int k = 0; k < 4; ++k)
              best = std::max(best, glm::dot(d, impostorFrameDirection(ci + (k & 1), cj + (k >> 1))));
            worst = std::max(worst, std::acos(std::clamp(best, -1.0, 1.0)));
          }
    return worst;
  }();
  return angle;
}

double impostorError(double radius) {
  return std::abs(radius) * (std::sin(impostorCoveringAngle()) + 2.0 / double(kImpostorFramePixels));
}

}  // namespace hs::render

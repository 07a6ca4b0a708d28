#include "app/overlay_shapes.h"

#include <cmath>

namespace hs::app {

double worldPerPixels(const render::RenderView& view, const glm::dvec3& p, double pixels) {
  const double depth = glm::dot(p - view.eye, view.forward());
  if (depth <= view.nearClip) return 0.0;
  return view.pixelSizeAt(depth) * pixels;
}

void circle(render::Overlay& o, const glm::dvec3& c, const glm::dvec3& u, const glm::dvec3& v, double r,
            const glm::vec4& col, int segments) {
  glm::dvec3 prev = c + u * r;
  for (int i = 1; i <= segments; ++i) {
    const double a = 2.0 * M_PI * i / segments;
    const glm::dvec3 p = c + (u * std::cos(a) + v * std::sin(a)) * r;
    o.line(prev, p, col);
    prev = p;
  }
}

void box(render::Overlay& o, const glm::dmat4& world, const glm::dvec3& mn, const glm::dvec3& mx,
         const glm::vec4& col) {
  glm::dvec3 c[8];
  for (int i = 0; i < 8; ++i)
    c[i] = glm::dvec3(world * glm::dvec4((i & 1) ? mx.x : mn.x, (i & 2) ? mx.y : mn.y, (i & 4) ? mx.z : mn.z, 1.0));
  const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& e : edges) o.line(c[e[0]], c[e[1]], col);
}

}  // namespace hs::app

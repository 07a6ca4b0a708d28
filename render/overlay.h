#pragma once
// Editor overlays drawn over the scene: gizmo handles, selection outlines,
// later camera paths and brush circles. World positions in double; the
// renderer makes them camera-relative.
#include <vector>

#include <glm/glm.hpp>

namespace hs::render {

struct OverlayVertex {
  glm::dvec3 position;
  glm::vec4 color;
};

struct Overlay {
  std::vector<OverlayVertex> lines;      // pairs
  std::vector<OverlayVertex> triangles;  // triples
  bool onTop = true;                     // ignore scene depth (gizmos)

  void line(const glm::dvec3& a, const glm::dvec3& b, const glm::vec4& c) {
    lines.push_back({a, c});
    lines.push_back({b, c});
  }
  void triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::vec4& col) {
    triangles.push_back({a, col});
    triangles.push_back({b, col});
    triangles.push_back({c, col});
  }
  bool empty() const { return lines.empty() && triangles.empty(); }
};

}  // namespace hs::render

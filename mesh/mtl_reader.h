#pragma once
// Wavefront MTL reader: the material names, diffuse colours and diffuse
// texture maps that OBJ photogrammetry exports use.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hs::mesh {

struct MtlMaterial {
  std::string name;
  glm::vec3 kd{0.8f};        // as written (sRGB-ish display colour)
  float opacity = 1.0f;      // "d", or 1 - "Tr"
  std::string diffuseMap;    // map_Kd file name, as written
};

// Appends the materials of `path` to `out`. Returns false with `error` (file
// and line) if the file cannot be read; unknown statements are ignored.
bool readMtl(const std::string& path, std::vector<MtlMaterial>& out, std::string& error);

}  // namespace hs::mesh

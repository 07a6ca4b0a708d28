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
// and line) if the file cannot be read or changed while it was read;
// unknown statements are ignored. `warnings` (optional) gets what was read
// but may be wrong: a last line without a line end (a file cut short).
bool readMtl(const std::string& path, std::vector<MtlMaterial>& out, std::string& error,
             std::vector<std::string>* warnings = nullptr);

}  // namespace hs::mesh

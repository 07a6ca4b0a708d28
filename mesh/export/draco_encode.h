#pragma once
// One glTF primitive compressed with Draco (KHR_draco_mesh_compression),
// as 3D Tiles content usually is (Cesium ion, RealityCapture and
// Metashape write it so): positions quantized on a grid of
// 2^bits - 1 steps across the primitive's largest extent, normals
// octahedral at 10 bits, UVs at 12 bits, connectivity by Edgebreaker.
// The grid is set explicitly (not left to Draco), so the distance each
// position moves is known exactly and reported.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hs::mesh::exporting {

struct DracoPrimitive {
  std::string bytes;             // the Draco bitstream
  uint32_t points = 0;           // what the decoder yields: the glTF accessors' count
  uint32_t faces = 0;
  int positionId = -1, normalId = -1, uvId = -1;  // Draco attribute ids (-1: absent)
  glm::vec3 lo{0.0f}, hi{0.0f};  // the positions' bounds (POSITION's min and max)
  double maxPositionError = 0.0; // the largest distance a position moved by quantization (file units)
};

inline constexpr int kDracoNormalBits = 10, kDracoUvBits = 12;

// `indices` (triangles) into `positions` and, when not empty, `normals`
// and `uvs` (same count); only the vertices the triangles use are encoded.
// `positionBits` in 8..30. False with `error` when Draco refuses.
bool encodeDraco(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                 const std::vector<glm::vec2>& uvs, const uint32_t* indices, size_t indexCount, int positionBits,
                 DracoPrimitive& out, std::string& error);

}  // namespace hs::mesh::exporting

#pragma once
// In-memory triangle mesh as the rest of Hybridscape sees it: float vertex
// data relative to a double-precision origin (DESIGN.md, coordinates), so a
// scan at UTM coordinates keeps millimetre precision.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hs::mesh {

// A texture image. `encoded` keeps the source file's bytes (PNG, JPEG, ...)
// when there were any, so a scene file stores the compact original; `rgba`
// is the decoded RGBA8 (sRGB) image the renderer uploads.
struct Texture {
  std::string name;            // file name or "*0" for embedded textures
  std::vector<uint8_t> encoded;
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;   // width * height * 4, sRGB-encoded
};

struct Material {
  std::string name;
  glm::vec4 baseColor{0.8f, 0.8f, 0.8f, 1.0f};  // linear RGB, alpha
  int diffuseTexture = -1;                        // index into MeshData::textures
};

struct Submesh {
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;
  int material = -1;  // index into MeshData::materials, -1 = default material
};

struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  bool empty = true;
  glm::vec3 center() const { return (min + max) * 0.5f; }
  float radius() const { return empty ? 0.0f : glm::length(max - min) * 0.5f; }
  void extend(const glm::vec3& p);
};

struct MeshData {
  glm::dvec3 origin{0.0};            // world-space position of local (0,0,0)
  std::vector<glm::vec3> positions;  // relative to origin, Z up, metres
  std::vector<glm::vec3> normals;    // one per position
  std::vector<glm::vec2> uvs;        // one per position, or empty
  std::vector<uint32_t> indices;     // triangle list
  std::vector<Submesh> submeshes;    // cover `indices`; at least one if any triangles
  std::vector<Material> materials;
  std::vector<Texture> textures;

  size_t vertexCount() const { return positions.size(); }
  size_t triangleCount() const { return indices.size() / 3; }
  Bounds bounds() const;
  // Bytes held by the vertex/index/texture arrays (for memory reports).
  size_t memoryBytes() const;
};

// Area-weighted vertex normals (generated only where a mesh has none).
void computeVertexNormals(MeshData& mesh, unsigned threads = 1);

// Per face: the material of the submesh it belongs to (-1 where none, or
// the default material). Material groups decide seams and which texture a
// face's UVs refer to.
std::vector<int> faceMaterials(const MeshData& mesh);

// Moves the origin to the centre of the bounding box so positions are small
// floats; the world position of every vertex stays the same to double precision.
void recenter(MeshData& mesh);

// 64-bit content hash (XXH3, core/content_hash.h) of everything a mesh blob
// stores: detects whether it changed since the last save, and checks it on load.
uint64_t contentHash(const MeshData& mesh);

}  // namespace hs::mesh

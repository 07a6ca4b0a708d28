#pragma once
// The triangles of a glTF 2.0 asset (GLB bytes, or .gltf JSON with its
// buffers), as 3D Tiles content carries them (mesh/tileset_reader.h): every
// triangle primitive of the default scene's nodes with the node transforms
// applied, in double, in glTF's own frame (y up; the tileset reader turns
// it z up). Draco-compressed primitives (KHR_draco_mesh_compression) are
// decoded with libdraco; quantized attributes (KHR_mesh_quantization's
// normalized integers) are read as glTF says.
//
// tinygltf parses the JSON, the GLB chunks and the buffers; the accessors
// and the Draco extension are read here, not by tinygltf, because tinygltf
// indexes its arrays with the file's numbers unchecked (its own Draco
// path too): every index, offset, stride and count is checked here against
// what is behind it, and a primitive that fails is skipped with a warning
// naming it (the asset's other primitives still come in).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hs::mesh {

struct GltfGeometry {
  std::vector<glm::dvec3> positions;  // glTF frame, node transforms applied
  std::vector<glm::vec2> uvs;         // TEXCOORD_0, one per position; empty if any primitive lacks it
  std::vector<uint32_t> indices;      // triangles
  size_t declaredTriangles = 0;       // what the triangle primitives' accessors declare
  std::optional<glm::dvec3> rtcCenter;  // the CESIUM_RTC extension's centre (older 3D Tiles content)
  std::vector<std::string> warnings;    // each starts with `what`
};

// `bytes` is a GLB when it starts with "glTF", else glTF JSON; `baseDir`
// resolves the JSON's external buffers. False with `error` (starting with
// `what`) when the asset cannot be parsed at all.
bool readGltfGeometry(const std::vector<uint8_t>& bytes, const std::string& baseDir, const std::string& what,
                      GltfGeometry& out, std::string& error);

}  // namespace hs::mesh

// Binary little-endian PLY: positions as float (relative) or double
// (world: UTM coordinates keep every digit), normals, `s t` texture
// coordinates, triangles as uchar-counted int lists; the first texture
// named in a `comment TextureFile` line (MeshLab's convention) and written
// beside. PLY has no materials: colours and textures beyond the first are
// not kept, and the header says so in a comment.
#include <bit>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include "mesh/export/export_geometry.h"

namespace hs::mesh::exporting {
namespace fs = std::filesystem;

namespace {

static_assert(std::endian::native == std::endian::little, "binary_little_endian is written from memory as it is");

template <class T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

}  // namespace

bool writePly(const MeshData& mesh, const Geometry& g, const std::string& path, const ExportOptions& o,
              PendingFiles& files, const Progress* progress, std::string& error) {
  if (g.positions.size() > size_t(INT32_MAX)) {
    error = path + ": " + std::to_string(g.positions.size()) + " vertices do not fit PLY's int indices";
    return false;
  }
  const fs::path dir = fs::path(path).parent_path();
  const std::string stem = fs::path(path).stem().string();
  std::string textureFile;
  int texture = -1;
  for (const Material& m : mesh.materials)
    if (m.diffuseTexture >= 0 && m.diffuseTexture < int(mesh.textures.size())) {
      texture = m.diffuseTexture;
      break;
    }
  if (texture >= 0 && !g.uvs.empty()) {
    std::string ext;
    const std::string bytes = textureFileBytes(mesh.textures[size_t(texture)], false, ext, error);
    if (bytes.empty()) {
      error = path + ": " + error;
      return false;
    }
    textureFile = stem + ext;
    if (!files.add((dir / textureFile).string(), bytes, error)) return false;
  }

  const bool hasUv = !g.uvs.empty(), hasNormals = !g.normals.empty();
  const char* coord = g.world ? "double" : "float";
  std::string h = "ply\nformat binary_little_endian 1.0\ncomment Hybridscape mesh export\n";
  if (!o.comment.empty()) h += "comment " + o.comment + "\n";
  h += std::string("comment ") + (g.world ? "world coordinates" : "coordinates relative to the origin in " + stem +
                                                                      "_offset.xyz (when present)") +
       ", " + (o.zUp ? "Z up" : "Y up") + ", metres\n";
  if (mesh.materials.size() > 1 || mesh.textures.size() > 1)
    h += "comment PLY holds one texture and no materials: " + std::to_string(mesh.materials.size()) +
         " materials were not written\n";
  if (!textureFile.empty()) h += "comment TextureFile " + textureFile + "\n";
  h += "element vertex " + std::to_string(g.positions.size()) + "\n";
  for (const char* a : {"x", "y", "z"}) h += std::string("property ") + coord + " " + a + "\n";
  if (hasNormals) h += "property float nx\nproperty float ny\nproperty float nz\n";
  if (hasUv) h += "property float s\nproperty float t\n";
  h += "element face " + std::to_string(g.indices.size() / 3) + "\n";
  h += "property list uchar int vertex_indices\nend_header\n";

  std::string out = std::move(h);
  const size_t vertexBytes = (g.world ? 24 : 12) + (hasNormals ? 12 : 0) + (hasUv ? 8 : 0);
  out.reserve(out.size() + g.positions.size() * vertexBytes + g.indices.size() / 3 * 13);
  for (size_t i = 0; i < g.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (g.world) put(out, g.positions[i][k]);
      else put(out, float(g.positions[i][k]));
    }
    if (hasNormals)
      for (int k = 0; k < 3; ++k) put(out, g.normals[i][k]);
    if (hasUv) {
      put(out, g.uvs[i].x);
      put(out, 1.0f - g.uvs[i].y);  // PLY's t points up, as OBJ's v
    }
  }
  if (isCancelled(progress)) return false;
  reportProgress(progress, 0.6, "Writing faces");
  for (size_t t = 0; t + 2 < g.indices.size(); t += 3) {
    put(out, uint8_t(3));
    for (int k = 0; k < 3; ++k) put(out, int32_t(g.indices[t + size_t(k)]));
  }
  return files.add(path, out, error);
}

}  // namespace hs::mesh::exporting

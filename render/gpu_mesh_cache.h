#pragma once
// GPU copies of mesh assets (vertex/index buffers, textures), uploaded on
// first use and dropped when the asset leaves the scene. Keyed by asset id
// and content hash, so a changed asset is re-uploaded and an unchanged one
// never is. LOD levels are uploaded when an instance first draws them, and
// draw with level 0's textures (they have none of their own).
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <epoxy/gl.h>

#include "mesh/mesh_data.h"
#include "scene/scene_state.h"

namespace hs::render {

struct GpuMesh {
  GLuint vao = 0;
  GLuint buffers[4] = {0, 0, 0, 0};  // positions, normals, uvs, indices
  std::vector<GLuint> textures;      // per mesh texture, sRGB with mipmaps
  std::shared_ptr<const mesh::MeshData> data;  // for submeshes/materials/bounds
  mesh::Bounds bounds;
  uint64_t hash = 0;
  size_t gpuBytes = 0;
  bool hasUvs = false;
  // Per submesh: the range its vertices' UVs span (min u, min v, max u,
  // max v); the shaders hold the UV they sample at to it (shaders/mesh_uv.glsl).
  std::vector<glm::vec4> uvBounds;
  bool ownsTextures = true;  // false for LOD levels: `textures` are level 0's
  // Attribute 3 (vec4, mesh/tangents.h), made only when a normal- or
  // height-mapped material draws the mesh (GpuMeshCache::addTangents).
  GLuint tangents = 0;
  size_t tangentBytes = 0;
  void release();  // GL objects; not in a destructor, the context may be gone
};

class GpuMeshCache {
 public:
  // The GPU mesh for level `level` of `asset` (0: MeshAsset::data; k: lods[k-1]),
  // uploading it if needed. Null if it has no data; level 0 for a level the
  // asset does not have.
  const GpuMesh* get(const scene::MeshAsset& asset, int level = 0);
  // Frees meshes (and levels) whose asset is gone from `state` or changed.
  void collect(const scene::SceneState& state);
  void clear();
  size_t gpuBytes() const;
  // The per-instance stream every mesh VAO reads at attribute 7 (the
  // object index of a draw: glDraw*BaseInstance picks it); set again when
  // the buffer grows.
  void setObjectIndexBuffer(GLuint buffer);
  // Computes and uploads `mesh`'s tangents (attribute 3) if it has none yet.
  void addTangents(const GpuMesh& mesh);
  // Bytes of every tangent stream (the registry lists them apart: a scene
  // without normal or height maps holds none).
  size_t tangentBytes() const;

 private:
  struct Entry {
    std::unique_ptr<GpuMesh> base;               // level 0, owns the textures
    std::vector<std::unique_ptr<GpuMesh>> lods;  // levels 1.., null until drawn
    void release();
  };
  std::map<scene::AssetId, Entry> meshes_;
  GLuint objectIndices_ = 0;
};

}  // namespace hs::render

#pragma once
// GPU copies of mesh assets (vertex/index buffers, textures), uploaded on
// first use and dropped when the asset leaves the scene. Keyed by asset id
// and content hash, so a changed asset is re-uploaded and an unchanged one
// never is.
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
  void release();  // GL objects; not in a destructor, the context may be gone
};

class GpuMeshCache {
 public:
  // The GPU mesh for `asset`, uploading it if needed. Null if it has no data.
  const GpuMesh* get(const scene::MeshAsset& asset);
  // Frees meshes whose asset is gone from `state`.
  void collect(const scene::SceneState& state);
  void clear();
  size_t gpuBytes() const;

 private:
  std::map<scene::AssetId, std::unique_ptr<GpuMesh>> meshes_;
};

}  // namespace hs::render

#pragma once
// Octahedral impostor atlases (impostor_atlas.h has their geometry), per
// mesh asset a type draws with an impostor level, kept on the GPU while
// what they were baked from is unchanged (scene/impostor_key.h): per type
// two textures of kImpostorFrames^2 frames of kImpostorFramePixels^2
// (768 x 768 with 5 mip levels, about 6.3 MB):
//   albedo        sRGB RGBA8: base colour x coverage, coverage
//   normalDepth   RGBA8: (mesh-space normal x 0.5 + 0.5, depth) x coverage
// (shaders/impostor_bake.frag writes them; shaders/impostor.frag reads).
// Where the scene stores current images (MeshAsset::impostor) they are
// uploaded (level 0, mips rebuilt: a few ms); else the bake draws level 0
// once per frame of the atlas with its materials' base colour and
// cut-out, on the render thread, in the first frame that needs it: that
// frame took 1.2 s on llvmpipe in test_impostors (the programs' first
// compile included; the next frame 10 ms). readBack gives a baked atlas to
// the scene to store (Renderer::bakeImpostor). Include only inside render/.
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "foliage/impostor_images.h"
#include "render/gl/gl_handle.h"
#include "render/material_table.h"
#include "scene/scene_state.h"

namespace hs::render {

struct GpuMesh;
struct RenderResources;

struct ImpostorAtlas {
  gl::Texture albedo, normalDepth;
  glm::vec4 sphere{0.0f};  // level 0's bounds: centre (mesh space), radius
  uint64_t sourceKey = 0;  // scene::impostorSourceKey of what it shows
  bool stored = false;     // uploaded from the scene's images (else baked here)
  size_t bytes = 0;
};

class ImpostorCache {
 public:
  // The atlas of `asset` for `sourceKey` (scene::impostorSourceKey): the
  // one kept, else the scene's stored images when they have that key, else
  // baked now from level 0 (`mesh`, drawn with `materials`, one per
  // submesh, from this frame's MaterialTable; needs the frame's material
  // block bound). Null for a mesh with empty bounds.
  const ImpostorAtlas* get(RenderResources& res, const scene::MeshAsset& asset, uint64_t sourceKey,
                           const GpuMesh& mesh, const std::vector<DrawMaterial>& materials);
  // Bakes `asset`'s atlas now whatever is kept or stored (as get() would
  // without them) and reads its level 0 back for the scene to store.
  std::optional<foliage::ImpostorImages> bakeAndRead(RenderResources& res, scene::AssetId asset, uint64_t sourceKey,
                                                     const GpuMesh& mesh, const std::vector<DrawMaterial>& materials);
  // How many atlases were baked and how many uploaded from stored images
  // since the renderer started (tests, frame stats).
  size_t bakes() const { return bakes_; }
  size_t uploads() const { return uploads_; }
  // Frees the atlases whose asset `state` no longer has.
  void collect(const scene::SceneState& state);
  void clear() { atlases_.clear(); }
  size_t gpuBytes() const;
  // The card every impostor draws: an element buffer of two triangles over
  // corners 0..3 (shaders/impostor.vert builds them from gl_VertexID).
  GLuint cardVao();

 private:
  ImpostorAtlas bake(RenderResources& res, uint64_t sourceKey, const GpuMesh& mesh,
                     const std::vector<DrawMaterial>& materials);
  static ImpostorAtlas upload(const foliage::ImpostorImages& images);

  std::map<scene::AssetId, ImpostorAtlas> atlases_;
  size_t bakes_ = 0, uploads_ = 0;
  gl::VertexArray cardVao_;
  gl::Buffer cardIndices_;
};

}  // namespace hs::render

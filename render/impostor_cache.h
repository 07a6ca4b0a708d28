#pragma once
// Octahedral impostor atlases (impostor_atlas.h has their geometry), baked
// by the renderer from a mesh asset's level 0 the first time an instanced
// source's type may draw its far level, and kept on the GPU while the
// asset is unchanged: per type two textures of kImpostorFrames^2 frames of
// kImpostorFramePixels^2 (768 x 768 with 5 mip levels, about 6.3 MB):
//   albedo        sRGB RGBA8: base colour x coverage, coverage
//   normalDepth   RGBA8: (mesh-space normal x 0.5 + 0.5, depth) x coverage
// (shaders/impostor_bake.frag writes them; shaders/impostor.frag reads).
// The bake draws level 0 once per frame of the atlas with its materials'
// base colour and cut-out, on the render thread, in the first frame that
// needs it: that frame took 1.2 s on llvmpipe in test_impostors (the
// programs' first compile included; the next frame 10 ms). The atlases are
// not kept in the .hscene (docs/rendering.md "Impostors"). Include only
// inside render/.
#include <cstdint>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "render/gl/gl_handle.h"
#include "render/material_table.h"
#include "scene/scene_state.h"

namespace hs::render {

struct GpuMesh;
struct RenderResources;

struct ImpostorAtlas {
  gl::Texture albedo, normalDepth;
  glm::vec4 sphere{0.0f};  // level 0's bounds: centre (mesh space), radius
  uint64_t meshHash = 0;   // GpuMesh::hash of the level 0 baked
  size_t bytes = 0;
};

class ImpostorCache {
 public:
  // The atlas of `asset`'s level 0 (`mesh`, drawn with `materials`, one
  // per submesh, from this frame's MaterialTable), baked now if there is
  // none for this mesh yet. Needs the frame's material block bound. Null
  // for a mesh with empty bounds.
  const ImpostorAtlas* get(RenderResources& res, scene::AssetId asset, const GpuMesh& mesh,
                           const std::vector<DrawMaterial>& materials);
  // Frees the atlases whose asset `state` no longer has.
  void collect(const scene::SceneState& state);
  void clear() { atlases_.clear(); }
  size_t gpuBytes() const;
  // The card every impostor draws: an element buffer of two triangles over
  // corners 0..3 (shaders/impostor.vert builds them from gl_VertexID).
  GLuint cardVao();

 private:
  std::map<scene::AssetId, ImpostorAtlas> atlases_;
  gl::VertexArray cardVao_;
  gl::Buffer cardIndices_;
};

}  // namespace hs::render

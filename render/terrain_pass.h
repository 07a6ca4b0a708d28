#pragma once
// Terrains on the GPU: every visible terrain entity of the scene, CDLOD-
// selected (terrain_lod.h) and drawn with one instanced call each. The
// frame graph's terrain pass (passes/scene_passes.cpp) calls draw(); a
// scene without terrains does not add that pass (no programs bound, no
// buffers touched, nothing uploaded). Lighting comes from the frame's
// blocks (lighting.glsl), as for meshes. Include only inside render/.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "render/gl/shader_library.h"
#include "render/gl_program.h"
#include "render/gpu_terrain.h"
#include "render/render_view.h"
#include "render/terrain_materials.h"
#include "scene/scene_state.h"

namespace hs::render {

struct TerrainFrameStats {
  size_t terrains = 0;
  size_t patches = 0;
  size_t triangles = 0;
  size_t nodesCulled = 0;
  double selectMs = 0.0;
  TerrainUploadStats upload;
};

class TerrainPass {
 public:
  // Builds its programs through `shaders`.
  bool initialize(gl::ShaderLibrary& shaders, std::string& error);
  void release();

  // Visible terrain entities of the scene (empty: the pass does not run).
  static std::vector<scene::EntityId> visibleTerrains(const scene::SceneState& state);

  // Draws into the bound framebuffer (depth test GREATER, reversed Z) with
  // the view block of `view` bound. Levels of detail and morphing come from
  // `lodView` (the frame's mono camera: both eyes draw the same levels).
  // `defines`: the shading program's variant (the frame's fog,
  // fog_block.h), built on first use.
  TerrainFrameStats draw(const scene::SceneState& state, const std::vector<scene::EntityId>& entities,
                         const RenderView& view, const RenderView& lodView,
                         const std::vector<std::string>& defines = {});
  // The id pass, with a (one-pixel) view block bound: `lodView` chooses the
  // levels (the real view). Terrain i gets id firstId + i.
  void drawPick(const scene::SceneState& state, const std::vector<scene::EntityId>& entities,
                const RenderView& lodView, unsigned firstId);

  // Depth only, for a shadow map (passes/shadow_passes.cpp), with the
  // cascade's view block bound: levels from `lodView` (so the terrain
  // shadows itself with the triangles the views draw), nodes culled against
  // `volume` (relative to lodView's eye) instead of the view's frustum.
  // Holes cast no shadow. Returns the triangles drawn.
  size_t drawShadow(const scene::SceneState& state, const std::vector<scene::EntityId>& entities,
                    const RenderView& lodView, const Frustum& volume);

  // Uploads what changed without drawing (benchmarks measure the upload alone).
  TerrainUploadStats sync(const scene::TerrainData& data);
  // The CDLOD selection the pass would draw for one terrain entity.
  LodSelection select(const scene::SceneState& state, scene::EntityId entity, const RenderView& view);

  size_t gpuBytes() const;
  // Material texture files that could not be read, each once, as found
  // since the last call ("terrain 'Valley', material 'Grass': albedo
  // texture PATH: reason"); a renderer finds them when it (re)loads a
  // terrain's textures, i.e. when a path changes.
  std::vector<std::string> takeMaterialProblems();

 private:
  struct Prepared {
    GpuTerrain* gpu = nullptr;
    const scene::TerrainAsset* asset = nullptr;
    LodSelection lod;
    glm::ivec2 cameraSample{0};
    glm::vec3 cameraRest{0.0f};
    glm::dvec3 lodEye{0.0};  // the view the levels were chosen from
  };
  // `cull`: planes to cull nodes against instead of the view's frustum.
  bool prepare(const scene::SceneState& state, scene::EntityId entity, const RenderView& view, Prepared& out,
               TerrainFrameStats* stats, const Frustum* cull = nullptr);
  void bindCommon(GlProgram& p, const Prepared& t, const RenderView& view);
  size_t drawInstances(const Prepared& t);
  void collect(const scene::SceneState& state);

  bool ready_ = false;
  GlProgram* shade_ = nullptr;
  gl::ShaderLibrary* shaders_ = nullptr;  // for the shading variants (shadingProgram)
  GlProgram* shadingProgram(const std::vector<std::string>& defines);
  GlProgram* pick_ = nullptr;
  GLuint vao_ = 0, gridVbo_ = 0, gridIbo_ = 0, instanceVbo_ = 0;
  size_t instanceCapacity_ = 0;
  GLsizei gridIndices_ = 0;
  GpuTerrainCache cache_;
  std::map<uint64_t, TerrainMaterialTextures> materials_;  // by TerrainData::instance()
  std::vector<std::string> newProblems_;
};

}  // namespace hs::render

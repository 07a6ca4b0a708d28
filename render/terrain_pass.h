#pragma once
// The terrain pass: every visible terrain entity of the scene, CDLOD-
// selected (terrain_lod.h) and drawn with one instanced call each, after the
// opaque meshes and before the sky. A scene without terrains does not run it
// (no programs bound, no buffers touched, nothing uploaded). Include only
// inside render/.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "render/gl_program.h"
#include "render/gpu_terrain.h"
#include "render/render_view.h"
#include "render/terrain_materials.h"
#include "scene/scene_state.h"

namespace hs::render {

// The frame's lights as the mesh pass sees them (view space).
struct TerrainLighting {
  bool hasSun = false;
  glm::vec3 sunDirView{0, 0, 1}, sunColor{0.0f}, upView{0, 0, 1};
  glm::vec3 sky{0.5f}, ground{0.2f};
  float ambient = 0.5f;
  int pointCount = 0;
  const glm::vec3* pointPosView = nullptr;
  const glm::vec3* pointColor = nullptr;
  const float* pointRange = nullptr;
};

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
  bool initialize(std::string& error);
  void release();

  // Visible terrain entities of the scene (empty: the pass does not run).
  static std::vector<scene::EntityId> visibleTerrains(const scene::SceneState& state);

  // Draws into the bound framebuffer (depth test GREATER, reversed Z).
  TerrainFrameStats draw(const scene::SceneState& state, const std::vector<scene::EntityId>& entities,
                         const RenderView& view, const TerrainLighting& lights);
  // The id pass: `lodView` chooses the levels (the real view), `projection`
  // draws (narrowed to one pixel). Terrain i gets id firstId + i.
  void drawPick(const scene::SceneState& state, const std::vector<scene::EntityId>& entities,
                const RenderView& lodView, const glm::mat4& projection, unsigned firstId);

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
  };
  bool prepare(const scene::SceneState& state, scene::EntityId entity, const RenderView& view, Prepared& out,
               TerrainFrameStats* stats);
  void bindCommon(GlProgram& p, const Prepared& t, const RenderView& view);
  size_t drawInstances(const Prepared& t);
  void collect(const scene::SceneState& state);

  bool ready_ = false;
  GlProgram shade_, pick_;
  GLuint vao_ = 0, gridVbo_ = 0, gridIbo_ = 0, instanceVbo_ = 0;
  size_t instanceCapacity_ = 0;
  GLsizei gridIndices_ = 0;
  GpuTerrainCache cache_;
  std::map<uint64_t, TerrainMaterialTextures> materials_;  // by TerrainData::instance()
  std::vector<std::string> newProblems_;
};

}  // namespace hs::render

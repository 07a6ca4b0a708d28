#pragma once
// The materials of one frame on the GPU: every submesh a visible draw
// shows gets its material (the document's, scene/material.h, through its
// asset's material slots; for an asset without slots, one made from its
// mesh::Material) as an index into the MaterialBlock storage buffer and
// its textures (base colour, normal map, height map: units 0-2). Textures
// of a mesh are its GpuMesh's; standalone ones are uploaded here, keyed by
// id and content hash. The base colour texture of an alpha cut-out
// material gets a copy of its own, keyed by the texture and the threshold,
// whose mip levels keep level 0's alpha coverage at that threshold
// (mesh/alpha_coverage_mips.h: far leaves do not vanish); a texture whose
// alpha is 255 everywhere needs none. A texture that cannot be drawn (missing, empty,
// larger than the GPU allows, damaged, a grey "normal map") is left out of
// the draw and reported once, naming the material and the field; the
// frame still renders. Include only inside render/.
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "render/gpu_material.h"
#include "scene/scene_state.h"

namespace hs::render {

class GpuMeshCache;
struct GpuMesh;
struct GrowingBuffer;
struct DrawItem;

struct DrawMaterial {
  uint32_t index = 0;                  // into the frame's MaterialBlock
  GLuint textures[3] = {0, 0, 0};      // base colour, normal map, height map
  scene::ShadingMode shading = scene::ShadingMode::Phong;
  bool twoSided = true;
  // Program variants (HAS_NORMAL_MAP, HAS_PARALLAX): only with a drawable
  // map, never with Gouraud shading (lit per vertex, before any map).
  bool normalMap = false;
  bool parallax = false;
  // Opacity under 1 and no alpha cut-out: drawn by the transparency path
  // (render/oit.h), not the opaque pass.
  bool translucent = false;
  // Shadow casting (shaders/shadow_depth.frag's ALPHA_CUTOUT variant): a
  // document material with alpha cut-out or opacity under 1 casts through
  // its holes (cut-out, at `alphaThreshold`) or a hashed share of its
  // surface (translucent); every other material casts as a solid.
  bool castsCutout = false;
  float opacity = 1.0f;
  float alphaThreshold = 0.5f;
  // The UV range of the drawn submesh (GpuMesh::uvBounds): the texture
  // lookups hold their UV to it (shaders/mesh_uv.glsl). All zero: none.
  glm::vec4 uvBounds{0.0f};
};

class MaterialTable {
 public:
  // Resolves the material of every submesh of every draw of `visible` (the
  // shadow-only casters' too) and uploads the block into `buffer` (bound at
  // kMaterialBufferBinding).
  // `depthOnly` is the range of draws only shadow views draw (no tangents
  // for them).
  void build(const scene::SceneState& state, const std::vector<DrawItem>& draws, std::pair<size_t, size_t> depthOnly,
             GpuMeshCache& meshes, GrowingBuffer& buffer);
  const DrawMaterial& forDraw(size_t draw, size_t submesh) const { return perDraw_[draw][submesh]; }
  size_t materialCount() const { return block_.size(); }

  // Frees standalone textures the state no longer has (or whose content changed).
  void collect(const scene::SceneState& state);
  void clear();
  size_t gpuBytes() const;
  // Problems found since the last call, each reported once.
  std::vector<std::string> takeProblems();

 private:
  struct Standalone {
    uint64_t hash = 0;
    GLuint texture = 0;
    size_t bytes = 0;
  };
  // `cutout`: the material's alpha threshold when it is cut out (the
  // coverage-preserving copy), else negative.
  GLuint texture(const scene::SceneState& state, const scene::Material& m, const char* field, scene::TextureId id,
                 const GpuMesh& mesh, GpuMeshCache& meshes, bool normalMap, float cutout = -1.0f);
  struct CutoutCopy {
    // The image it was made from, held so that a new image is never at the
    // same address (the copy is made again when the texture's image changes).
    std::shared_ptr<const mesh::Texture> image;
    GLuint texture = 0;
    size_t bytes = 0;
    bool used = false;            // by the last build (collect frees the others)
  };
  GLuint cutoutTexture(scene::TextureId id, const std::shared_ptr<const mesh::Texture>& image, bool srgb,
                       float threshold);
  void report(const std::string& problem);

  std::vector<GpuMaterial> block_;
  std::map<scene::MaterialId, DrawMaterial> byId_;  // this frame's
  std::vector<std::vector<DrawMaterial>> perDraw_;  // [draw][submesh]
  std::map<scene::TextureId, Standalone> standalone_;
  std::map<std::pair<scene::TextureId, int>, CutoutCopy> cutout_;  // (texture, threshold x 255)
  std::set<std::string> reported_;
  std::vector<std::string> problems_;
  int maxTextureSize_ = 0;
};

}  // namespace hs::render

#pragma once
// A draw source for many instances of a few meshes (foliage, scattered
// rocks; draw_source.h): instances in the compact 32-byte format below,
// grouped in cells whose origins are kept in double and sent relative to
// the frame origin. Each frame, for every instance, once:
//   - its level of detail, from its type's mesh asset's LOD chain by the
//     rule of mesh_lod.h chooseMeshLod, seen from the frame's LOD view
//     (FrameContext::lodView), so both eyes and every shadow view draw the
//     level a mesh entity at that place would draw; past the chain's last
//     level, an octahedral impostor (impostor_atlas.h, baked by
//     impostor_cache.h, drawn by shaders/impostor.vert and .frag: one card
//     an instance) whose error is impostorError of level 0's bounding
//     radius (at least the last level's). A type has that level only where
//     some instance can reach it: the pixel bound is above 0 and the
//     distance the impostor's error passes from, at the type's smallest
//     instance scale, within its cull distance; else no atlas is baked
//     (the layered depth of field's capture takes impostors too, with
//     impostor.frag's A-buffer variants);
//   - whether it is beyond its type's cull distance from the LOD eye (then
//     no view draws it); over the last InstanceType::fadeLength metres
//     before it, mesh.vert gives it a fade share and every fragment shader
//     that draws it discards that share of its pixels by an ordered 8x8
//     dither (shaders/instance_fade.glsl): lit, shadow depth, picking and
//     the transparency passes alike, so its shadow fades with it;
// then, for each view (the camera views, then the shadow views; a type
// that does not cast shadows is in none of those), the sphere test. A
// view's list is sorted into draw groups (type, level), and each view draws
// one instanced draw per part (a submesh of a group's mesh), in one of two
// ways:
//   Culling::Gpu  compute passes ("<name>_cull": shaders/instance_lod.comp,
//                 instance_groups.comp, instance_cull.comp and
//                 instance_commands.comp) write the levels, the groups'
//                 places, the visible lists and the indirect commands; the
//                 passes draw them with glMultiDrawElementsIndirect, the
//                 CPU never sees a count (they come back a frame later,
//                 FrameGraph::readback, for the statistics);
//   Culling::Cpu  the CPU chooses (chooseMeshLod itself, in double), culls
//                 (the same sphere test, in double) and uploads the lists;
//                 glDrawElementsInstanced. The reference the tests compare
//                 the GPU's choices with.
// Both draw with mesh.vert's INSTANCED variant and the type's materials;
// the instance's stable id reaches the fragment shader as vObject (the id
// pass writes pickBase + id, the transparency key hashes it with the
// primitive). Vertices sway in the wind (instanceWindOffset below) as a
// pure function of the frame's time. The instance data lives in a
// persistent buffer of the frame graph, uploaded when setInstances changed
// it. Include only inside render/.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "render/draw_source.h"
#include "render/instance_format.h"
#include "render/visible_set.h"

namespace hs::render {

class MaterialTable;
struct ImpostorAtlas;

// One instance (std430, shaders/instances.glsl), 32 bytes.
struct GpuInstance {
  glm::vec3 position{0.0f};  // relative to its cell's origin (m)
  // The scale as two halves, packHalf2x16(xy, z): one factor across (x and
  // y of the mesh) and one along its height (z); equal for a uniform scale.
  // Halves keep 11 significant bits (0.05 %), as close as the foliage
  // store's own encoding and more; the struct stays 32 bytes.
  uint32_t scaleXyZ = 0x3C003C00u;           // (1, 1)
  uint32_t rotation[2] = {0, 0x7FFF0000u};  // unit quaternion (x, y | z, w) as snorm16 pairs
  uint32_t typeAndCell = 0;                 // type | cell << 16
  uint32_t id = 0;                          // stable: picking, the transparency key
};
static_assert(sizeof(GpuInstance) == kGpuInstanceBytes);

// Packs an instance; `rotation` is normalised first. `scaleXyZ`: x the
// factor across (mesh x and y), y the factor along the height (mesh z).
GpuInstance packInstance(const glm::vec3& positionInCell, const glm::quat& rotation, glm::vec2 scaleXyZ,
                         uint16_t type, uint16_t cell, uint32_t id);
// A uniform scale (both halves `scale`).
GpuInstance packInstance(const glm::vec3& positionInCell, const glm::quat& rotation, float scale, uint16_t type,
                         uint16_t cell, uint32_t id);
// The rotation an instance stores (after snorm16 rounding, normalised).
glm::quat instanceRotation(const GpuInstance& instance);
// The scale an instance stores per mesh axis (xy, xy, z), after half rounding.
glm::vec3 instanceScale(const GpuInstance& instance);

// Wind (shaders/instances.glsl instanceWindOffset, the same model in
// float; this copy is for tests and bounds). A vertex `heightAboveOrigin`
// metres above the instance's origin along the mesh's z (before scale),
// of a mesh whose bounds reach `meshHeight` above it, on an instance
// scaled by `scaleZ` along z, moves by a main bend along the fixed wind
// direction kWindDirection (a steady lean plus a 0.5 Hz sway) and a
// smaller gust across it (1.3 Hz flutter under a 0.2 Hz envelope), each
// instance in its own phase (a hash of its id). The bend grows with the
// square of the relative height h = clamp(height / meshHeight, 0, 1) (a
// cantilever's first mode, roughly): at the top the bend moves up to
// kWindBend x response x the instance's height along the wind (2 % per
// unit of response), the gust up to 0.3 of that across it; the vertex
// also drops by the move's square over twice its height, so a bent stem
// keeps about its length (docs/rendering.md "Instanced sources").
// Response 0 moves nothing (the shader does not even evaluate it). The
// frequencies are multiples of 1/60 Hz and the shader folds t to t mod
// 60 s using FrameBlock.time's double-taken fraction, so a frame late in a
// long shot sways as exactly as the first.
inline constexpr float kWindBend = 0.02f;
inline const glm::vec2 kWindDirection{0.8f, 0.6f};  // towards east-north-east, unit
glm::vec3 instanceWindOffset(float response, float heightAboveOrigin, float meshHeight, float scaleZ, uint32_t id,
                             double seconds);
// The most instanceWindOffset can move any vertex of an instance whose
// height (mesh bounds top x |scaleZ|) is `worldHeight`: the cull sphere
// grows by it, so culling stays conservative in the wind.
float instanceWindMargin(float response, float worldHeight);

// How an instance type is drawn (foliage/foliage_type.h has the
// document's side of these).
struct InstanceType {
  scene::AssetId mesh = scene::kNoAsset;  // a mesh asset of the document; its LOD chain and materials draw it
  // Metres from the LOD view's eye to the instance's origin beyond which
  // no view draws it; 0: never culled by distance.
  float cullDistance = 0.0f;
  // Metres before cullDistance over which it fades out (dithered): the
  // share of its pixels dropped grows linearly from 0 to 1. 0: no fade.
  float fadeLength = 0.0f;
  // 0: stiff (a rock, no displacement at all); 1: a tree's sway; up to 10.
  float windResponse = 0.0f;
  bool castShadows = true;  // false: left out of every shadow view
  // Beyond the last mesh level, an octahedral impostor (the foliage's
  // types: FoliageType::impostor); false: the mesh levels only, however far.
  bool impostor = false;
  bool operator==(const InstanceType&) const = default;
};

// The most instances one source culls on the GPU: its compute passes run
// one invocation per instance in groups of 64, and GL promises no more than
// 65,535 groups in a dispatch (llvmpipe allows no more); their 32 bytes
// each then just fit the 128 MiB GL promises a storage buffer. A source of
// more draws nothing: split the set (foliage_instances.h does).
constexpr size_t kMaxInstancesPerSource = 65535 * 64;

struct InstanceSet {
  std::vector<InstanceType> types;  // an instance's type indexes this
  std::vector<glm::dvec3> cells;    // world origins of the cells
  std::vector<GpuInstance> instances;
  scene::EntityId entity = scene::kNoEntity;  // what picking an instance names, with its id
};

class InstancedSource final : public DrawSource {
 public:
  enum class Culling { Cpu, Gpu };
  InstancedSource(std::string name, Culling culling);
  ~InstancedSource() override;

  // Replaces the instances (uploaded by the next frame that draws them).
  void setInstances(InstanceSet set);
  // Replaces instances [first, first + n) in place (an edit of a few cells,
  // foliage_sources.h): the next frame uploads those ranges into the buffer
  // it keeps instead of the whole set. The types and cells stay.
  void updateInstances(size_t first, const GpuInstance* items, size_t n);
  // Appends a cell (its world origin) for instances updateInstances puts
  // in spare places to name: a new foliage cell in a set's spare tail
  // (foliage_sources.h), no upload of the set. Returns its index.
  uint16_t addCell(const glm::dvec3& origin);
  // Bytes of instances the last frame that drew this source uploaded (the
  // whole set after setInstances or a new buffer, else the updated ranges).
  size_t lastUploadBytes() const { return *lastUploadBytes_; }
  const InstanceSet& instances() const { return set_; }
  Culling culling() const { return culling_; }
  // Visible instances summed over the camera views of a frame that has been
  // delivered (GPU: a frame or more late; CPU: the last frame); -1: none yet.
  int64_t lastVisible() const { return *lastVisible_; }
  // The same, per level of detail (index: the level, over every type);
  // empty: none yet.
  std::vector<int64_t> lastVisibleByLevel() const { return *lastByLevel_; }

  // For tests: from the next frame on, also report which instances each
  // camera view drew and at which level (GPU: the compute pass's lists,
  // read back a frame or more late like the counts; CPU: the CPU's lists).
  // Off by default: the read-back copies a list per camera view each frame.
  struct KeptInstance {
    uint32_t id = 0;     // GpuInstance::id
    uint32_t level = 0;  // the level it was drawn at
  };
  void setReportKept(bool on) { reportKept_ = on; }
  // Triangles the camera views drew (every surface), as lastVisible: a
  // frame or more late on the GPU path; -1: none yet.
  int64_t lastTrianglesDrawn() const { return *lastTriangles_; }
  // Benchmarks: false skips the sphere test against the views (every
  // instance within its cull distance is drawn by every view), the naive
  // baseline culling is measured against. On by default.
  void setViewCulling(bool on) { viewCulling_ = on; }
  // Per camera view of the last delivered frame, in the list's order
  // (GPU: the atomics' order); empty: none delivered yet.
  std::vector<std::vector<KeptInstance>> lastKept() const { return *lastKept_; }

  std::string ownPass() const override { return name_; }
  bool has(DrawVariant variant, SurfaceSet surfaces) const override;
  void addMaterials(FrameContext& frame, std::vector<DrawItem>& draws) override;
  void addPreparePasses(FrameGraph& graph, FrameContext& frame) override;
  void declare(PassBuilder& builder, DrawVariant variant) const override;
  void draw(FrameContext& frame, const DrawCall& call, const PassResources& resources) override;
  size_t triangles(SurfaceSet surfaces) const override;
  // The nearest corner of its cells' instance boxes, less the farthest
  // reach of a type's mesh (its bounds and wind margin at the largest
  // scale): conservative, from the CPU's copy of the set.
  double nearestDepth(const RenderView& view) const override;
  uint32_t pickIds() const override { return maxId_ + 1; }
  // Whether the last frame drew (could draw) type `type` as an impostor:
  // the type has that level this frame and its atlas is baked.
  bool impostorLevel(size_t type) const { return type < types_.size() && types_[type].impostor != nullptr; }
  PickedItem picked(uint32_t k) const override { return {set_.entity, k}; }

 private:
  // This frame's view of a type: its asset, its draw groups (one per level
  // of its LOD chain: firstGroup .. firstGroup + levels - 1; levels 0: its
  // asset is gone, it draws nothing), the sphere that chooses its level
  // (level 0's bounds, mesh space), a radius about the same centre that
  // holds every level, and its wind's height and margin.
  struct TypeFrame {
    const scene::MeshAsset* asset = nullptr;
    uint32_t firstGroup = 0, levels = 0;
    glm::vec4 lodSphere{0.0f, 0.0f, 0.0f, -1.0f};
    float cullRadius = 0.0f;
    float height = 0.0f;           // level 0's bounds top above the origin (m, mesh space; 0: no wind)
    float windPerScaleZ = 0.0f;    // instanceWindMargin per unit |scale z|
    std::vector<double> errors;    // MeshAsset::lodErrors(), then the impostor's
    // The impostor level (the last, group firstGroup + levels - 1) when the
    // type has one this frame: its atlas (baked by addPreparePasses) and
    // the submesh of level 0 whose material lights it (the largest).
    bool hasImpostor = false;
    const ImpostorAtlas* impostor = nullptr;
    uint32_t impostorSubmesh = 0;
  };
  struct Group {
    uint32_t type = 0, level = 0;
    const GpuMesh* mesh = nullptr;  // the level's (level 0's where the cache has no such level); null: the impostor
    size_t materialDraw = 0;        // its draw in the MaterialTable (the impostor: level 0's)
  };
  struct Part {
    uint32_t group = 0, type = 0, firstIndex = 0, indexCount = 0, submesh = 0;
  };
  bool wanted(const Part& part, SurfaceSet surfaces) const;
  void drawParts(FrameContext& frame, const PassResources& r, size_t view, const DrawCall& call);
  void drawPart(FrameContext& frame, size_t view, size_t k, const DrawCall& call, uint32_t firstIndex);
  void drawImpostors(FrameContext& frame, size_t view, const DrawCall& call, glm::ivec2 ditherOffset);
  void bindInstances(const PassResources& r) const;

  std::string name_, bufferName_;
  Culling culling_;
  InstanceSet set_;
  uint64_t revision_ = 1, uploaded_ = 0;
  // Ranges (first, count) updateInstances changed since the last upload.
  std::vector<std::pair<size_t, size_t>> pending_;
  std::shared_ptr<size_t> lastUploadBytes_ = std::make_shared<size_t>(0);
  uint32_t maxId_ = 0;
  // This frame's types, groups and parts, the MaterialTable, the LOD eye
  // relative to the frame origin, and the frame's resources.
  std::vector<TypeFrame> types_;
  std::vector<Group> groups_;
  std::vector<Part> parts_;
  const MaterialTable* materials_ = nullptr;
  glm::vec3 lodEye_{0.0f};
  std::vector<uint32_t> cpuCounts_;  // Cpu: visible per view and group
  std::vector<float> minScale_;      // per type: its instances' smallest largest |scale| factor
  float maxScale_ = 0.0f;            // every instance's largest |scale| factor
  // Per cell: the box its instances' positions lie in (relative to the
  // cell's origin; min > max: none yet). Widened by updates, never shrunk.
  std::vector<std::pair<glm::vec3, glm::vec3>> cellBoxes_;
  void widen(const GpuInstance& g);
  size_t cameraViews_ = 0;
  bool anyCaster_ = false;
  BufferRef instanceBuffer_, cells_, visible_, groupBase_, commands_;
  bool active_ = false;  // something to draw this frame
  std::shared_ptr<int64_t> lastVisible_ = std::make_shared<int64_t>(-1);
  std::shared_ptr<std::vector<int64_t>> lastByLevel_ = std::make_shared<std::vector<int64_t>>();
  bool reportKept_ = false, viewCulling_ = true;
  std::shared_ptr<int64_t> lastTriangles_ = std::make_shared<int64_t>(-1);
  std::shared_ptr<std::vector<std::vector<KeptInstance>>> lastKept_ =
      std::make_shared<std::vector<std::vector<KeptInstance>>>();
};

}  // namespace hs::render

#pragma once
// Mesh particles (particles::EmitterDesc::drawMesh; docs/particles.md,
// "Drawing"): an emitter whose draw_mesh names a mesh entity draws each
// live particle as that entity's mesh asset (its LOD chain and materials),
// through the instanced source (instanced_source.h) rather than a mesh
// path of its own: one InstancedSource for every mesh-drawing emitter of
// the frame (CPU culling: deterministic), one instance type per emitter,
// one cell per emitter at its world origin (double), one instance per
// particle. So mesh particles are opaque (or whatever the mesh's materials
// are), lit, cast and receive shadows, choose a level of detail per
// particle and are culled per view (camera and shadow views) as foliage is.
// Include only inside render/.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "mesh/mesh_data.h"
#include "particles/evaluate.h"
#include "render/draw_source.h"
#include "render/instanced_source.h"
#include "scene/scene_state.h"

namespace hs::render {

// The unit axis a mesh particle turns about: uniform over the sphere, a
// pure function of the particle's random bits (PackedParticle::variant,
// itself a hash of the emitter's seed and the particle's id).
glm::dvec3 meshParticleAxis(uint32_t variant);

// Where a particle puts its mesh, relative to its emitter's origin: the
// mesh's own origin at `offset`, turned by `rotation`, scaled by `scale`
// (uniform), so that a mesh vertex v lands at offset + rotation (scale v).
struct MeshParticlePose {
  glm::dvec3 offset{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  double scale = 0.0;
};

// The largest extent of level 0's bounds (the box's longest side); 0 for
// empty bounds.
double meshLargestExtent(const mesh::Bounds& level0);

// A particle at `position` (relative to its emitter's origin) of `size`
// (Particle::size) and `rotationDeg` (Particle::rotationDeg, spin
// included): the mesh scaled so its largest extent is `size`, turned by
// rotationDeg about meshParticleAxis(variant), its bounds' centre on the
// position (so it turns about its middle, as a sprite does). Scale 0 when
// the bounds have no extent.
MeshParticlePose meshParticlePose(const mesh::Bounds& level0, const glm::dvec3& position, double size,
                                  double rotationDeg, uint32_t variant);

// One frame's mesh particles as a draw source: clear(), add() per emitter,
// commit(); then it draws what its InstancedSource draws (kept across
// frames, so its instance buffer is the same persistent buffer while the
// count stays). Picking a mesh particle names its emitter's entity.
class MeshParticleSource final : public DrawSource {
 public:
  MeshParticleSource();
  ~MeshParticleSource() override;

  void clear();
  // Adds `frame`'s particles of the emitter (`desc.origin` in world) of
  // entity `entity`, drawn as `asset`; returns how many became instances
  // (those of size above 0). At most 65536 emitters a frame (the
  // instance's 16-bit type and cell): past that none is added and `error`
  // says so.
  size_t add(scene::EntityId entity, const particles::EmitterDesc& desc, const scene::MeshAsset& asset,
             const particles::Frame& frame, std::string& error);
  // Hands the frame's instances to the instanced source; returns their
  // number (0: nothing to draw this frame).
  size_t commit();
  const InstanceSet& instances() const { return inner_.instances(); }

  std::string ownPass() const override { return inner_.ownPass(); }
  bool has(DrawVariant variant, SurfaceSet surfaces) const override { return inner_.has(variant, surfaces); }
  void cullShadowViews(FrameContext& frame, size_t first, size_t count) override {
    inner_.cullShadowViews(frame, first, count);
  }
  void addMaterials(FrameContext& frame, std::vector<DrawItem>& draws) override { inner_.addMaterials(frame, draws); }
  void addPreparePasses(FrameGraph& graph, FrameContext& frame) override { inner_.addPreparePasses(graph, frame); }
  void declare(PassBuilder& builder, DrawVariant variant) const override { inner_.declare(builder, variant); }
  void draw(FrameContext& frame, const DrawCall& call, const PassResources& resources) override {
    inner_.draw(frame, call, resources);
  }
  size_t triangles(SurfaceSet surfaces) const override { return inner_.triangles(surfaces); }
  uint32_t pickIds() const override { return inner_.pickIds(); }
  PickedItem picked(uint32_t k) const override;

 private:
  // Level 0's bounds of an asset, computed once per mesh data.
  const mesh::Bounds& boundsOf(const scene::MeshAsset& asset);

  InstancedSource inner_;
  InstanceSet next_;
  std::vector<std::pair<uint32_t, scene::EntityId>> firstIds_;  // per emitter: its first instance id
  std::vector<std::pair<uint32_t, scene::EntityId>> pickRanges_;  // the committed frame's
  std::map<scene::AssetId, std::pair<std::shared_ptr<const mesh::MeshData>, mesh::Bounds>> bounds_;
};

}  // namespace hs::render

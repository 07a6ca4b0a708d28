#pragma once
// The scene's particle emitters as a draw source (docs/particles.md,
// "Drawing"; docs/rendering.md, "Particles"). Each frame every visible
// emitter is evaluated once on the CPU at the frame's scene time
// (particles::Evaluator::frame, with a ReplayCache per entity kept across
// frames), packed relative to the frame origin (camera-relative, formed in
// double), culled against the frame's views, and uploaded into one storage
// buffer that every view (both eyes) draws from. Billboards are pulled from
// that buffer in shaders/particle.vert; they are translucent surfaces only:
// they draw in the frame's transparency passes, every mode, so they sort
// against glass, water and each other, and in the layered depth of field's
// capture (each blurred by its own depth). No shadows, no picking. A frame without a live particle in
// view adds no pass, buffer or texture. Emitters with a draw_mesh draw
// their particles as that entity's mesh instead, through a second source
// (particle_mesh.h: instances, lit, casting shadows), made only in a frame
// where such an emitter has live particles. Include only inside render/.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "particles/evaluate.h"
#include "render/draw_source.h"
#include "render/particle_gpu_eval.h"
#include "render/particle_mesh.h"
#include "render/particle_sprites.h"
#include "scene/particle_world.h"
#include "scene/scene_state.h"

namespace hs::render {

// One emitter's share of the frame's particle buffer and how it draws.
struct ParticleDraw {
  uint32_t first = 0, count = 0;
  int layerBase = 0, layerCount = 1;  // ParticleSprites
  bool additive = false, lit = true, alongVelocity = false;
  float softDistance = 0.0f;          // metres; 0: hard
  uint32_t object = 0;                // the transparency key's object
};

// An emitter the compute pass evaluates (RenderOptions::gpuParticles):
// its records go from `first` in the frame's buffer.
struct ParticleGpuJob {
  GpuEmitterData data;
  uint32_t first = 0;
};

// One frame's particles (made by ParticleSources::update): the CPU's
// records first, then the compute pass's.
class ParticleSource final : public DrawSource {
 public:
  // `origin`: the frame origin the records are relative to; `gpuBounds`:
  // per GPU job a sphere (world centre, radius; radius below 0: none
  // known) that holds its particles.
  ParticleSource(ParticleSprites& sprites, std::vector<particles::PackedParticle> particles,
                 std::vector<ParticleGpuJob> gpuJobs, std::vector<ParticleDraw> draws, size_t views,
                 const glm::dvec3& origin, std::vector<glm::dvec4> gpuBounds);
  bool has(DrawVariant variant, SurfaceSet surfaces) const override;
  void addPreparePasses(FrameGraph& graph, FrameContext& frame) override;
  void declare(PassBuilder& builder, DrawVariant variant) const override;
  void draw(FrameContext& frame, const DrawCall& call, const PassResources& resources) override;
  size_t triangles(SurfaceSet surfaces) const override;
  // The nearest particle's depth (its quad's half diagonal before it).
  double nearestDepth(const RenderView& view) const override;
  size_t recordCount() const { return records_; }

 private:
  ParticleSprites& sprites_;
  std::vector<particles::PackedParticle> particles_;
  std::vector<ParticleGpuJob> gpuJobs_;
  size_t records_ = 0;  // the CPU's and the compute pass's
  std::vector<ParticleDraw> draws_;
  size_t views_ = 1;
  glm::dvec3 origin_{0.0};
  std::vector<glm::dvec4> gpuBounds_;
  BufferRef buffer_{};
};

// The renderer's particle state across frames: evaluators and replay
// caches per entity (rebuilt when the entity's emitter changes, or when
// the meshes and terrains it collides with or is born on change), the
// collision world, the sprite array.
class ParticleSources {
 public:
  ParticleSources();
  ~ParticleSources();
  // The frame's sprite source (null: no live sprite particle in any view
  // of `frame`); meshes() then has the frame's mesh particles. Adds to
  // frame.stats.particlesDrawn (sprites in the buffer, mesh particles
  // handed to the instanced source).
  DrawSource* update(const scene::SceneState& state, FrameContext& frame);
  // The last update's mesh particles (null: no emitter drew meshes).
  DrawSource* meshes() const { return meshesActive_ ? meshes_.get() : nullptr; }
  // Emitters the last update left out: "emitter 'X', field ..." (the
  // evaluator refused it, or its draw_mesh names no mesh entity).
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  struct Entry {
    scene::PlacedEmitter placed{};  // what it was made from
    std::optional<particles::Evaluator> evaluator;
    particles::ReplayCache cache;
    std::string error;
    uint64_t worldKey = 0;  // the collision world it was made with (0: none needed)
    bool evaluated = false;
    double time = 0.0;      // the scene time `frame` is for
    particles::Frame frame{};
  };
  Entry& entryFor(const scene::SceneState& state, const scene::PlacedEmitter& placed);
  // The entry's particles at t, evaluated once per scene time (a second
  // view group or a lens sample of the same frame reuses them).
  const particles::Frame& frameAt(Entry& e, double t);

  // The terrain's samples for the compute pass's collisions (uploaded for
  // the collision world `terrainHeightsKey_` when a GPU job first collides
  // with the terrain; freed after a frame where none does).
  unsigned terrainHeightsFor(const terrain::Heightfield& hf);

  std::map<scene::EntityId, Entry> entries_;
  gl::Buffer terrainHeights_;
  uint64_t terrainHeightsKey_ = 0;
  std::unique_ptr<scene::ParticleWorld> world_;
  const scene::SceneState* worldState_ = nullptr;
  uint64_t worldKey_ = 0;
  ParticleSprites sprites_;
  std::unique_ptr<ParticleSource> source_;
  std::unique_ptr<MeshParticleSource> meshes_;  // made when an emitter first draws meshes
  bool meshesActive_ = false;
  std::vector<std::string> errors_;
};

}  // namespace hs::render

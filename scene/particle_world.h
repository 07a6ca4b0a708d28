#pragma once
// A scene's particle emitters where they are, and what their particles meet
// (docs/particles.md, "In the document"): the one place editor, CLI, info
// and renderer turn an entity's ParticleEmitter into something
// particles::Evaluator takes, so they cannot disagree on an origin, a
// collider or a mesh surface.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "particles/bounds.h"
#include "particles/evaluate.h"
#include "scene/emitter_tracks.h"
#include "scene/foliage_ground.h"
#include "scene/scene_state.h"
#include "sequencer/sequence.h"

namespace hs::scene {

// The entity's emitter with its world origin (the entity's world
// translation plus desc.origin) and its name (the entity's); nullopt if the
// entity has no emitter.
std::optional<particles::EmitterDesc> emitterInWorld(const SceneState& state, EntityId id);

// An emitter's world origin over scene time, what world space needs
// (particles::EvaluatorInputs::originAt): its entity's world translation
// from the transform tracks and camera paths of the entity and its parents
// (the rest of the chain as the state has it), plus desc.origin. A pure
// function of time, so a particle born at t_b starts at originAt(t_b) on
// any frame and any farm node. Tracks are evaluated directly (a few binary
// searches a particle); a path in the chain evaluates the sequence (its
// aims at other entities use their animated translations, the sequencer's
// rule without positions). Two are equal when they give the same origins.
class EmitterMotion {
 public:
  // Null when the emitter is in local space or nothing in its chain moves.
  static std::shared_ptr<const EmitterMotion> of(const SceneState& state, EntityId id);
  glm::dvec3 originAt(double t) const;
  // A box holding originAt(t) for every t in [t0, t1], proven from the
  // tracks' value ranges (sequencer::valueRange): each parent maps the box
  // exactly while it does not turn or scale, and into a ball while it does.
  // A camera path in the chain: its whole curve's box (sequencer::
  // PathSampler::box, the spans' Bézier hulls), with what lies below it as
  // a ball (the path's aim may turn it any way).
  std::optional<particles::OriginBox> originRange(double t0, double t1) const;
  bool operator==(const EmitterMotion& o) const;

 private:
  struct Level {
    EntityId id = kNoEntity;
    Transform transform{};
    std::optional<sequencer::Binding> binding{};  // a copy; none: not animated
  };
  std::vector<Level> levels_;  // the entity first, then its parents
  glm::dvec3 offset_{0.0};     // desc.origin
  std::shared_ptr<const sequencer::CompiledSequence> compiled_;  // the state's sequence, only with a path in the chain
};

// The mesh asset a draw_mesh name draws (particles/emitter.h): that of the
// first entity (lowest id) called `name` with a mesh component whose asset
// is in the document with vertices, visible or hidden (a source hidden so
// it is not drawn at its own place still lends its mesh). null: none.
const MeshAsset* drawMeshAsset(const SceneState& state, const std::string& name);
// "emitter 'NAME', field 'draw_mesh': no entity 'X' with a mesh".
std::string drawMeshProblem(const particles::EmitterDesc& desc);

struct PlacedEmitter {
  EntityId entity = kNoEntity;
  particles::EmitterDesc desc{};  // origin in world, name the entity's
  std::shared_ptr<const EmitterMotion> motion{};  // world space on a moving chain; else null
  std::shared_ptr<const EmitterSpawnTracks> spawn{};  // spawn values keyed on the timeline; else null
  // Whether `o` evaluates to the same particles (same emitter, motion and tracks).
  bool sameAs(const PlacedEmitter& o) const;
};
// What the placed emitter adds to an evaluator's inputs: its origin over
// time (world space) and its keyed spawn values, each kept alive by them.
void addTimeInputs(const PlacedEmitter& placed, particles::EvaluatorInputs& in);
// The entity's emitter placed (nullopt: it has none), what visibleEmitters
// gives for each and the editor's overlay for the selected one.
std::optional<PlacedEmitter> placedEmitter(const SceneState& state, EntityId id);
// Every effectively visible emitter, depth-first (outliner order).
std::vector<PlacedEmitter> visibleEmitters(const SceneState& state);

// What particles collide with and are born on: the first visible terrain
// (the ground of `terrain` shapes and a collider) and the visible mesh
// entities (colliders; a `mesh` shape's surface is the mesh entity of that
// name, its level 0 in world space). What an emitter needs is built when
// first asked for: the terrain (no samples copied), the meshes' BVHs only
// for an emitter that collides (what the meshes cost). Keep one while the
// scene's entities and assets stay; it refers to `state`, which must outlive it.
class ParticleWorld {
 public:
  explicit ParticleWorld(const SceneState& state) : state_(state) {}
  ParticleWorld(const ParticleWorld&) = delete;
  ParticleWorld& operator=(const ParticleWorld&) = delete;

  // The evaluator's inputs for `desc` (world origin): colliders when it
  // collides, the ground when its shape is `terrain`, the surface when it is
  // `mesh` (null when no visible mesh entity has that name: Evaluator::create
  // then refuses with "the mesh '...' is missing").
  // `colliders` false: none even for a colliding emitter (counting the live
  // particles needs no replay, so no BVH).
  // Only the colliders its particles can reach: a collider whose box misses
  // the sphere that holds every particle the emitter can have
  // (particles::particleBound, widened by 1 m) is left out, which changes no
  // result (no step's segment can meet it: both ends are in the sphere) and
  // saves its ray casts, and an emitter with nothing in reach is not
  // replayed for collisions at all (closed form without turbulence; the
  // compute pass can take it). `fixed` false: the emitter moves or has
  // spawn tracks (PlacedEmitter::motion, ::spawn), whose particles that
  // bound does not hold: every collider.
  particles::EvaluatorInputs inputs(const particles::EmitterDesc& desc, bool colliders = true, bool fixed = true);
  // The evaluator for `desc`, or nullopt with `error` naming emitter and field.
  // The terrain's world z range (its lowest and highest sample), what
  // particles::particleBound needs for a `terrain` shape; nullopt without a
  // visible terrain.
  std::optional<std::pair<double, double>> groundRange();
  // The terrain collider inputs() gives (null: no visible terrain) and the
  // heights it reads (world: origin, spacing, samples, holes), what a GPU
  // evaluation of the same collisions uploads.
  const particles::HeightFieldCollider* terrainCollider();
  const terrain::Heightfield* terrainHeights();
  std::optional<particles::Evaluator> evaluator(const particles::EmitterDesc& desc, std::string& error,
                                                bool colliders = true);
  // With the placed emitter's time inputs (addTimeInputs).
  std::optional<particles::Evaluator> evaluator(const PlacedEmitter& placed, std::string& error,
                                                bool colliders = true);

 private:
  void buildTerrain();
  void buildMeshes();

  const SceneState& state_;
  std::unique_ptr<FoliageGround> terrainGround_, meshGround_;  // in world space
  bool terrainBuilt_ = false, meshesBuilt_ = false;
  // A collider with the world box it can be met in.
  template <class C>
  struct Boxed {
    std::unique_ptr<C> collider;
    glm::dvec3 lo{0.0}, hi{0.0};
  };
  std::optional<Boxed<particles::HeightFieldCollider>> terrain_;
  std::vector<Boxed<particles::RaycastCollider>> meshes_;
  std::vector<std::unique_ptr<particles::TriangleSurface>> surfaces_;  // kept for evaluators made here
};

// The bound of a placed emitter's particles alive at scene time t
// (particles/bounds.h) with what the scene knows: for a moving world-space
// emitter where it was over their births ([t - lifetime_max, t]), its spawn
// tracks' values over them, the ground's height range (`world`, needed
// for a terrain shape) and a mesh shape's surface. `desc` is the emitter
// widened by its spawn tracks, what a draw's reach reads (sizes, speeds).
// nullopt: none can be given (see particleBound; a camera path moving a
// world-space emitter).
struct PlacedBound {
  particles::EmitterDesc desc{};
  particles::ParticleBound bound{};
};
std::optional<PlacedBound> placedBound(const PlacedEmitter& placed, double t, ParticleWorld* world,
                                       const particles::SurfaceSampler* surface);
// The live particles of every visible emitter at the state's time, as
// `info --time` lists them: by lifetimes, before a collision's kills
// (Evaluator::liveCount; `estimated` past 2^24 candidates).
struct EmitterCount {
  EntityId entity = kNoEntity;
  std::string name;
  uint64_t live = 0;
  bool estimated = false;
  std::string error;  // an emitter the evaluator refuses, or whose draw_mesh is missing: why
};
std::vector<EmitterCount> liveParticleCounts(const SceneState& state, double t);

}  // namespace hs::scene

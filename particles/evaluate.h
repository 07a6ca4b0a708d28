#pragma once
// Particles as a pure function of time (docs/particles.md; DESIGN.md,
// "Time and determinism"): particle (stream, index)'s birth, initial state
// and random numbers come from the counter-based hash of (seed, stream,
// index) (rng.h, spawn.h); its state at scene time t is
//   - closed form when only gravity, drag and constant wind act
//     (motion.h: exact for every k, k dt and t, no history);
//   - with turbulence or collision, a fixed-step replay from the particle's
//     birth: steps of the emitter's replay_step_s on a grid anchored at the
//     birth (never the frame rate's, never the first frame's), each step
//     the exact motion under the step's forces (turbulence at the step's
//     predicted midpoint: second order), collisions located on the exact
//     trajectory inside the step. A ReplayCache keeps each particle's state
//     at its last whole step, so the next frame resumes there: the same
//     steps in the same order, so the result is bit-identical with and
//     without it.
// Frame N evaluated alone equals frame N evaluated after frames 0..N-1, bit
// for bit, on any thread count.
//
// Positions and velocities are relative to the emitter's origin (double),
// so an emitter at UTM coordinates loses nothing; colliders work in world
// coordinates (origin + position).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "particles/collider.h"
#include "particles/emitter.h"
#include "particles/motion.h"
#include "particles/spawn.h"

namespace hs::particles {

// A point on a mesh emitter's surface, emitter-relative.
struct SurfacePoint {
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0, 0.0, 1.0};
};

// The mesh shape's source: a point of the surface for three uniform random
// numbers in [0, 1), area-weighted. The scene implements it over its mesh
// assets; TriangleSurface below over a triangle list.
class SurfaceSampler {
 public:
  virtual ~SurfaceSampler() = default;
  virtual SurfacePoint sample(double u0, double u1, double u2) const = 0;
  // A box (emitter-relative min, max) holding every point sample() can
  // give; nullopt when not known (then no bound: particles/bounds.h).
  virtual std::optional<std::pair<glm::dvec3, glm::dvec3>> box() const { return std::nullopt; }
};

class TriangleSurface : public SurfaceSampler {
 public:
  explicit TriangleSurface(std::vector<glm::dvec3> corners);  // 3 per triangle, emitter-relative
  SurfacePoint sample(double u0, double u1, double u2) const override;
  std::optional<std::pair<glm::dvec3, glm::dvec3>> box() const override;  // of the corners
  bool empty() const { return cdf_.empty() || cdf_.back() <= 0.0; }

 private:
  std::vector<glm::dvec3> corners_;
  std::vector<double> cdf_;
};

// Stream 0: the rate's particles; stream b + 1: burst b's.
struct ParticleId {
  uint32_t stream = 0;
  uint64_t index = 0;
  bool operator==(const ParticleId&) const = default;
};

enum class Fate : uint8_t { Flying, Resting, Killed };

struct Particle {
  ParticleId id{};
  double birth = 0.0, lifetime = 0.0, age = 0.0;
  glm::dvec3 position{0.0};  // relative to the emitter's origin
  glm::dvec3 velocity{0.0};
  double size = 0.0;          // metres
  double rotationDeg = 0.0;
  glm::dvec4 colour{1.0};     // linear RGB, opacity
  int frame = 0;              // flipbook frame
  Fate fate = Fate::Flying;
  bool alive = false;         // born, not past its lifetime, not killed by a collision
  bool operator==(const Particle&) const = default;
};

// What a particle starts with (its random draws made concrete).
struct ParticleStart {
  double birth = 0.0, lifetime = 0.0, size = 0.0, rotationDeg = 0.0, spinDegPerS = 0.0;
  Kinematics state{};
};

// The replay's state of one particle at a whole step.
struct ReplayState {
  Kinematics k{};
  Fate fate = Fate::Flying;
  double fateTime = 0.0;  // scene time of the kill or the rest
  uint64_t step = 0;      // whole steps done since birth
  bool operator==(const ReplayState&) const = default;
};

// Per-particle replay states of one emitter, reused across frames. Changing
// the emitter (its JSON) empties it; an evaluator with other colliders
// needs a cache of its own.
class ReplayCache {
 public:
  size_t size() const { return entries_.size(); }
  void clear() { entries_.clear(); }
  uint64_t hits = 0, misses = 0;  // resumed / replayed from birth

 private:
  friend class Evaluator;
  struct Key {
    uint32_t stream;
    uint64_t index;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    size_t operator()(const Key& k) const { return std::hash<uint64_t>()(k.index * 0x9e3779b97f4a7c15ULL ^ k.stream); }
  };
  struct Entry {
    ReplayState state;
    uint64_t frame = 0;
  };
  uint64_t emitterKey_ = 0;
  uint64_t frameCounter_ = 0;
  std::unordered_map<Key, Entry, KeyHash> entries_;
};

struct Frame {
  double t = 0.0;
  std::vector<Particle> particles;  // alive ones, oldest first
  uint64_t live = 0;                // alive by their lifetimes, before the cap
  uint64_t leftOut = 0;             // of those, left out by max_live
  bool leftOutExact = true;         // false: counted by expectation (too many to count)
  uint64_t killed = 0;              // kept by the cap but killed by a collision before t
  uint64_t replaySteps = 0;         // replay steps this frame took (work)
  std::string message;              // the cap's message, naming the emitter, when something was left out
};

// What a draw source uploads for one particle: floats, the position relative
// to `relativeTo` (the camera's world position, say) formed in double
// before the conversion, so an emitter and a camera at UTM coordinates lose
// nothing (DESIGN.md, "Coordinates and scale"). 64 bytes (std430: four vec4s).
struct PackedParticle {
  float position[3];
  float size;
  float colour[4];  // linear RGB, opacity
  float velocity[3];
  float rotationDeg;
  uint32_t frame;    // flipbook frame
  uint32_t variant;  // a random 32 bits of the particle (sprite variants, flicker)
  uint32_t pad[2];
};
static_assert(sizeof(PackedParticle) == 64);
std::vector<PackedParticle> packFrame(const Frame& frame, const glm::dvec3& emitterOrigin, const glm::dvec3& relativeTo,
                                      uint32_t seed = 0);

// The emitter's values a particle takes at its birth: what timeline tracks
// on an emitter may animate (docs/particles.md, "On the timeline"). A
// particle samples them once, at its birth time, and keeps them (Niagara's
// spawn parameters): particles alive when a value changes are not moved,
// the motion stays closed form and a frame a pure function of t. Lifetime
// (it sizes the live window) and the forces (the motion's closed form and
// the replay) are per emitter; the wind and the rate have keys of their own.
struct SpawnValues {
  double speedMin = 0.0, speedMax = 0.0, sizeMin = 0.0, sizeMax = 0.0;
  double rotationMinDeg = 0.0, rotationMaxDeg = 0.0, spinMinDegPerS = 0.0, spinMaxDegPerS = 0.0;
  double spreadDeg = 0.0, coneAngleDeg = 0.0, radius = 0.0;
  glm::dvec3 direction{0.0, 0.0, 1.0}, boxHalf{0.0};
};
SpawnValues spawnValues(const EmitterDesc& e);
// The declared keys a track may animate, sampled at birth: speed_m_per_s
// size_m rotation_deg spin_deg_per_s (MIN,MAX pairs: a track sets the
// centre, the pair's half-width stays) spread_deg cone_angle_deg radius_m
// direction box_half_m. One table in evaluate.cpp says which member each
// key is; everything below reads it.
const std::vector<std::string>& spawnKeys();
bool isSpawnKey(std::string_view key);
// A spawn key's place in spawnKeys() (what a per-particle loop keeps
// instead of the name); -1 for any other key.
int spawnSlot(std::string_view key);
// The numbers a key's track carries: 3 for direction and box_half_m, 1 for
// the rest (a pair's centre); 0 for a key that is no spawn value.
size_t spawnValueCount(std::string_view key);
// The value of `key` in `v` as a track carries it (a pair's centre); empty
// for a key that is no spawn value.
std::vector<double> spawnValue(const SpawnValues& v, std::string_view key);
// Writes a track's value into `v`, held to the field's declared range (a
// pair's centre moved, its half-width kept; a zero direction ignored):
// by slot (spawnSlot; spawnValueCount numbers), or by key, false for a key
// that is no spawn value or a value of the wrong size.
void setSpawnValue(SpawnValues& v, int slot, const double* value);
bool setSpawnValue(SpawnValues& v, std::string_view key, const double* value, size_t count);

struct EvaluatorInputs {
  const SurfaceSampler* surface = nullptr;  // the mesh shape's surface
  std::vector<const Collider*> colliders{};
  const HeightFieldCollider* ground = nullptr;  // the terrain shape's ground (world coordinates)
  // World space (EmitterDesc::space): the emitter's world origin at a scene
  // time, a pure function of it (the scene evaluates its entity's animated
  // transform); a particle starts where the emitter was at its birth, and
  // desc.origin (where it is at the frame's time) stays the frame of the
  // results. Empty, or local space: the emitter never moved. A mesh shape's
  // particles are born on the surface where the surface is (it is another
  // entity's).
  std::function<glm::dvec3(double)> originAt{};
  // Spawn values keyed on the timeline: given a birth time and the
  // emitter's own values, writes the animated ones (a pure function of the
  // birth time). Empty: the emitter's values for every particle.
  std::function<void(double, SpawnValues&)> spawnAt{};
};

class Evaluator {
 public:
  // nullopt with the first problem of validate() (naming the emitter and the
  // field), or a mesh shape without a surface.
  static std::optional<Evaluator> create(const EmitterDesc& e, EvaluatorInputs inputs, std::string& error);

  const EmitterDesc& desc() const { return e_; }
  const EvaluatorInputs& inputs() const { return in_; }
  const SpawnSchedule& schedule() const { return spawn_; }
  uint64_t key() const { return key_; }
  bool replays() const { return replay_; }
  // World space with an origin that moves (EvaluatorInputs::originAt).
  bool movesInWorld() const { return e_.space == Space::World && bool(in_.originAt); }
  // Spawn values animated on the timeline (EvaluatorInputs::spawnAt).
  bool animatesSpawn() const { return bool(in_.spawnAt); }

  double birth(ParticleId id) const;
  ParticleStart start(ParticleId id) const;
  // Particle `id` at scene time t (alive false before its birth and after its
  // death). The cache, when given, is read and updated.
  Particle particle(ParticleId id, double t, ReplayCache* cache = nullptr) const;
  // Every live particle at t, oldest first, at most max_live of them.
  Frame frame(double t, ReplayCache* cache = nullptr, int threads = 0) const;

  // Without evaluating anyone: the particles born in the live window at t
  // (an upper bound of the live ones; O(1) plus the bursts: 0 means the
  // emitter costs nothing at t), and the live count by lifetimes before the
  // cap (what `info --time` lists; particles a collision kills are not
  // known without the replay and count as live; past 2^24 candidates it is
  // estimated, `estimated` says so).
  uint64_t candidates(double t) const;
  uint64_t liveCount(double t, bool* estimated = nullptr) const;

  // The replay's state at scene time t from `from` (a state at a whole step
  // of the particle born at `birth`), stepping on the birth-anchored grid.
  // `stepsTaken` counts the work.
  ReplayState replayTo(const ReplayState& from, double birth, double t, uint64_t& stepsTaken,
                       ReplayState* atLastWholeStep = nullptr) const;

 private:
  Evaluator(const EmitterDesc& e, EvaluatorInputs inputs);
  struct Candidate {
    ParticleId id;
    ParticleStart start;  // only the birth until frame() fills the rest
  };
  struct Census {
    uint64_t live = 0;
    bool estimated = false;
  };
  // The live window's census in birth order; the first `cap` alive ones go to `kept`.
  Census census(double t, uint64_t cap, std::vector<Candidate>* kept) const;
  ParticleStart startAt(ParticleId id, double birthTime) const;
  void advance(ReplayState& s, double t0, double tau) const;
  Particle finish(ParticleId id, const ParticleStart& st, const ReplayState& rs, double t) const;

  EmitterDesc e_;
  EvaluatorInputs in_;
  SpawnSchedule spawn_;
  Forces forces_{};
  uint64_t key_ = 0;
  bool replay_ = false;
  bool collide_ = false;
};

}  // namespace hs::particles

#pragma once
// GPU evaluation of an emitter (shaders/particle_eval.comp): the live
// window's candidates at scene time t computed by a compute pass, one
// invocation each, into particles::PackedParticle records, with
// particles::Evaluator as the reference (test_particle_gpu_eval holds them
// together within stated tolerances). Turbulence is replayed from each
// particle's birth on the CPU's step grid, every frame (no cache on the
// GPU: a frame costs the live particles' ages over the step, where the
// CPU's warm cache costs one frame's steps; bench_particles_render).
// Collisions with the scene's terrain are replayed there too (its samples
// uploaded once, gpuTerrainHeights; the CPU's ray cast and contact rules).
// What it takes: no collider but that terrain (a mesh in reach keeps the
// emitter on the CPU), at most 20000 replay steps for the oldest candidate, a point, box, sphere,
// disc or cone shape, a constant wind, at most 63 rate keys and 16 keys
// per life curve, and no more candidates than max_live (so the cap keeps
// all of them). The
// candidates not alive at t are written with size and opacity 0
// (particle.vert draws nothing for them) and frame kGpuNotAlive; records are in the CPU's
// candidate order (the rate's window, then each burst) and carry the
// particle's stream and index in the record's padding. Include only inside
// render/.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "particles/evaluate.h"
#include "terrain/heightfield.h"

namespace hs::render {

class GlProgram;

constexpr uint32_t kGpuNotAlive = 0xFFFFFFFFu;  // a record's frame: the candidate is not alive at t

// The terrain the compute pass can collide with (scene::ParticleWorld's
// terrain collider, recognised among an evaluator's colliders, and the
// heights it reads), and its samples as uploaded (`heights`: a buffer
// holding gpuTerrainHeights(*heightfield); 0 until it is).
struct GpuTerrainCollider {
  const particles::HeightFieldCollider* collider = nullptr;
  const terrain::Heightfield* heightfield = nullptr;
  unsigned heights = 0;
};
// The samples as particle_eval.comp reads them: row by row, relative to the
// origin's z, NaN at a hole.
std::vector<float> gpuTerrainHeights(const terrain::Heightfield& hf);

// Whether the compute pass can evaluate `ev` at t (colliding with nothing
// or only with `terrain`'s collider); if not, `why` says so.
bool gpuEvaluable(const particles::Evaluator& ev, double t, std::string* why = nullptr,
                  const GpuTerrainCollider* terrain = nullptr);
// Whether `ev` collides with the terrain (then its job needs terrain->heights).
bool collidesWithTerrain(const particles::Evaluator& ev, const GpuTerrainCollider* terrain);

// What the compute pass reads for one emitter at t: its doubles and its
// integers (the candidate ranges included), how many candidates, and the
// terrain's heights buffer when it collides with it.
struct GpuEmitterData {
  std::vector<double> doubles;
  std::vector<uint32_t> ints;
  uint32_t candidates = 0;
  unsigned terrainHeights = 0;
};
// Records are relative to `relativeTo` (the frame origin), formed in
// double; `packSeed` as packFrame's seed (the record's variant bits).
// `terrain`: what gpuEvaluable was given.
GpuEmitterData gpuEmitterData(const particles::Evaluator& ev, double t, const glm::dvec3& relativeTo,
                              uint32_t packSeed, const GpuTerrainCollider* terrain = nullptr);

// Runs `program` (particle_eval.comp) over `data`, writing records
// [first, first + data.candidates) of `out`; the emitter's two buffers are
// made and freed here.
void dispatchGpuEvaluation(GlProgram& program, const GpuEmitterData& data, unsigned out, uint32_t first);

}  // namespace hs::render

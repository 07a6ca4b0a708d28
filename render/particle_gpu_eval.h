#pragma once
// GPU evaluation of an emitter without replay (shaders/particle_eval.comp):
// the live window's candidates at scene time t computed by a compute pass,
// one invocation each, into particles::PackedParticle records, with
// particles::Evaluator as the reference (test_particle_gpu_eval holds them
// together within stated tolerances). What it takes: no turbulence, no
// collision (no replay), a point, box, sphere, disc or cone shape, a
// constant wind, at most 63 rate keys and 16 keys per life curve, and no
// more candidates than max_live (so the cap keeps all of them). The
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

namespace hs::render {

class GlProgram;

constexpr uint32_t kGpuNotAlive = 0xFFFFFFFFu;  // a record's frame: the candidate is not alive at t

// Whether the compute pass can evaluate `ev` at t; if not, `why` says so.
bool gpuEvaluable(const particles::Evaluator& ev, double t, std::string* why = nullptr);

// What the compute pass reads for one emitter at t: its doubles and its
// integers (the candidate ranges included), and how many candidates.
struct GpuEmitterData {
  std::vector<double> doubles;
  std::vector<uint32_t> ints;
  uint32_t candidates = 0;
};
// Records are relative to `relativeTo` (the frame origin), formed in
// double; `packSeed` as packFrame's seed (the record's variant bits).
GpuEmitterData gpuEmitterData(const particles::Evaluator& ev, double t, const glm::dvec3& relativeTo,
                              uint32_t packSeed);

// Runs `program` (particle_eval.comp) over `data`, writing records
// [first, first + data.candidates) of `out`; the emitter's two buffers are
// made and freed here.
void dispatchGpuEvaluation(GlProgram& program, const GpuEmitterData& data, unsigned out, uint32_t first);

}  // namespace hs::render

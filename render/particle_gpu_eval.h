#pragma once
// An emitter's particles at a scene time, evaluated on the GPU in a compute
// pass (shaders/particle_eval.comp) into the 64-byte records a particle draw
// source reads (particles::PackedParticle, std430): the closed form of
// particles/evaluate.h, with the CPU implementation as its reference
// (tests/render/test_particle_gpu_eval: every record against the CPU's).
//
// What it covers: emitters that need no replay (no turbulence, no
// collision with a collider), with constant wind, born from a point, box,
// sphere, disc or cone, and whose candidates at t fit under max_live (so no
// cap applies). Everything else stays on the CPU (Evaluator::frame), which
// also serves `info` and machines without compute.
//
// One record per candidate (the rate's birth window, then each burst still
// within a lifetime), written whether the particle is alive or not: a dead
// one has size 0 and draws nothing. The records' order is the candidates'
// (not the CPU frame's oldest-first across streams), and no atomic decides
// a place, so a frame's records are the same bits every time.
// Include only inside render/.
#include <cstdint>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/vec3.hpp>

#include "particles/evaluate.h"
#include "render/gl/gl_handle.h"

namespace hs::render {

namespace gl {
class ShaderLibrary;
}

class ParticleGpuEval {
 public:
  // Whether `ev`'s emitter can be evaluated here at t (see above); `why`
  // says what keeps it on the CPU.
  static bool supports(const particles::Evaluator& ev, double t, std::string* why = nullptr);
  // The records evaluate() writes for `ev` at t.
  static uint64_t records(const particles::Evaluator& ev, double t);

  // Writes records(ev, t) records into `buffer` from record `first`, with
  // positions relative to `relativeTo` (formed in double: the emitter's
  // origin minus it). The dispatches are issued; the caller's barrier makes
  // them visible. False with `error` (a program that does not build).
  bool evaluate(gl::ShaderLibrary& shaders, const particles::Evaluator& ev, double t, const glm::dvec3& relativeTo,
                GLuint buffer, uint64_t first, std::string& error);

 private:
  gl::Buffer schedule_, curves_;
};

}  // namespace hs::render

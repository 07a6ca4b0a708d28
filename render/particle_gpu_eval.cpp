#include "render/particle_gpu_eval.h"

#include <algorithm>
#include <cmath>

#include "render/gl/shader_library.h"

namespace hs::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// One dispatch: a stream's candidates [first index, + count).
struct Job {
  uint32_t stream = 0;
  uint64_t index = 0, count = 0;
  double burstTime = 0.0;
};

std::vector<Job> jobsAt(const particles::Evaluator& ev, double t) {
  std::vector<Job> jobs;
  const particles::EmitterDesc& e = ev.desc();
  const double window = e.lifetimeMax;
  const uint64_t k0 = ev.schedule().bornBy(t - window), k1 = ev.schedule().bornBy(t);
  if (k1 > k0) jobs.push_back({0, k0, k1 - k0, 0.0});
  for (size_t b = 0; b < e.bursts.size(); ++b) {
    const particles::Burst& burst = e.bursts[b];
    if (burst.t <= t && t - burst.t < window && burst.count > 0)
      jobs.push_back({uint32_t(b + 1), 0, uint64_t(burst.count), burst.t});
  }
  return jobs;
}

void upload(gl::Buffer& buffer, const void* data, size_t bytes) {
  if (!buffer) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    buffer = gl::Buffer(id);
  }
  // At least one element: an empty SSBO binding is an error on some drivers.
  static const float kZero[4] = {};
  glNamedBufferData(buffer.id(), GLsizeiptr(bytes ? bytes : sizeof kZero), bytes ? data : kZero, GL_STREAM_DRAW);
}

}  // namespace

bool ParticleGpuEval::supports(const particles::Evaluator& ev, double t, std::string* why) {
  const particles::EmitterDesc& e = ev.desc();
  auto no = [why](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (ev.replays()) return no("turbulence or collision needs the replay");
  if (!e.windKeys.empty()) return no("keyed wind");
  if (e.shape == particles::Shape::Mesh || e.shape == particles::Shape::Terrain) return no("a mesh or terrain shape");
  if (records(ev, t) > uint64_t(e.maxLive)) return no("more candidates than max_live (the cap applies)");
  if (records(ev, t) > (uint64_t(1) << 31)) return no("more than 2^31 candidates");
  return true;
}

uint64_t ParticleGpuEval::records(const particles::Evaluator& ev, double t) {
  uint64_t n = 0;
  for (const Job& j : jobsAt(ev, t)) n += j.count;
  return n;
}

bool ParticleGpuEval::evaluate(gl::ShaderLibrary& shaders, const particles::Evaluator& ev, double t,
                               const glm::dvec3& relativeTo, GLuint buffer, uint64_t first, std::string& error) {
  GlProgram* p = shaders.get({"", "", "particle_eval.comp", {}}, error);
  if (!p) return false;
  const particles::EmitterDesc& e = ev.desc();
  const particles::SpawnSchedule& s = ev.schedule();

  std::vector<double> schedule;
  for (size_t i = 0; i < s.boundaries().size(); ++i)
    schedule.insert(schedule.end(), {s.boundaries()[i], s.rates()[i], s.cumulative()[i]});
  upload(schedule_, schedule.data(), schedule.size() * sizeof(double));
  std::vector<glm::vec4> curves;
  for (const particles::CurveKey& k : e.sizeOverLife.keys) curves.emplace_back(float(k.t), float(k.value), 0.0f, 0.0f);
  for (const particles::ColourKey& k : e.colourOverLife.keys) {
    curves.emplace_back(float(k.t), 0.0f, 0.0f, 0.0f);
    curves.emplace_back(glm::vec4(k.rgba));
  }
  upload(curves_, curves.data(), curves.size() * sizeof(glm::vec4));

  const GLuint id = p->id();
  p->use();
  glProgramUniform1d(id, p->loc("t"), t);
  p->set("seed", unsigned(e.seed));
  p->set("boundaries", int(s.boundaries().size()));
  p->set("shape", unsigned(e.shape));
  p->set("surfaceOnly", e.surfaceOnly);
  p->set("alongNormal", e.alongNormal);
  p->set("direction", glm::vec3(ev.desc().direction));
  p->set("spreadRad", float(e.spreadDeg * kPi / 180.0));
  p->set("boxHalf", glm::vec3(e.boxHalf));
  p->set("radius", float(e.radius));
  p->set("coneRad", float(e.coneAngleDeg * kPi / 180.0));
  p->set("speed", glm::vec2(float(e.speedMin), float(e.speedMax)));
  p->set("lifetime", glm::vec2(float(e.lifetimeMin), float(e.lifetimeMax)));
  p->set("size", glm::vec2(float(e.sizeMin), float(e.sizeMax)));
  p->set("rotationDeg", glm::vec2(float(e.rotationMinDeg), float(e.rotationMaxDeg)));
  p->set("spinDegPerS", glm::vec2(float(e.spinMinDegPerS), float(e.spinMaxDegPerS)));
  p->set("gravity", glm::vec3(e.gravity));
  p->set("drag", float(e.drag));
  p->set("wind", glm::vec3(e.wind));
  p->set("flipbookFrames", e.flipbookFrames);
  p->set("sizeKeys", int(e.sizeOverLife.keys.size()));
  p->set("colourKeys", int(e.colourOverLife.keys.size()));
  p->set("offset", glm::vec3(e.origin - relativeTo));  // double, then float
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, schedule_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, curves_.id());
  // GL guarantees 65535 work groups per dispatch: larger jobs go in pieces.
  constexpr uint64_t kPiece = 65535u * 64u;
  uint64_t out = first;
  for (const Job& j : jobsAt(ev, t)) {
    glProgramUniform1d(id, p->loc("burstTime"), j.burstTime);
    p->set("stream", unsigned(j.stream));
    for (uint64_t done = 0; done < j.count; done += kPiece) {
      const uint64_t n = std::min(kPiece, j.count - done), index = j.index + done;
      glProgramUniform2ui(id, p->loc("indexBase"), uint32_t(index), uint32_t(index >> 32));
      p->set("count", unsigned(n));
      p->set("outBase", unsigned(out));
      glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
      out += n;
    }
  }
  return true;
}

}  // namespace hs::render

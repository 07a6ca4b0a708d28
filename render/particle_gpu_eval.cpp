#include "render/particle_gpu_eval.h"

#include <algorithm>
#include <limits>
#include <string>

#include <epoxy/gl.h>

#include "render/gl/gl_handle.h"
#include "render/gl_program.h"

namespace hs::render {
namespace {

// Slots of the doubles and integers (shaders/particle_eval.comp; keep in step).
enum : size_t {
  D_OFFSET = 0, D_T = 3, D_LIFE = 4, D_SIZE = 6, D_ROT = 8, D_SPIN = 10, D_SPEED = 12, D_DIR = 14, D_SPREAD = 17,
  D_BOX = 18, D_RADIUS = 21, D_CONE = 22, D_GRAVITY = 23, D_DRAG = 26, D_WIND = 27, D_SEGMENTS = 32,
  MAX_SEGMENTS = 64, D_SIZE_KEYS = 224, MAX_KEYS = 16, D_COLOUR_KEYS = 256, D_BURST_BIRTH = 352,
  MAX_BURSTS = 64, D_TURBULENCE = D_BURST_BIRTH + MAX_BURSTS + 1, D_STEP = D_TURBULENCE + 3, D_ORIGIN = D_STEP + 1,
  D_TERRAIN = D_ORIGIN + 3, D_COLLIDE = D_TERRAIN + 6, D_COUNT = D_COLLIDE + 3,
};
enum : size_t {
  U_SEED = 0, U_SHAPE = 1, U_SURFACE_ONLY = 2, U_ALONG_NORMAL = 3, U_FLIPBOOK = 4, U_SIZE_KEYS = 5,
  U_COLOUR_KEYS = 6, U_RANGES = 7, U_PACK_SEED = 8, U_SEGMENTS = 9, U_REPLAY = 10, U_COLLIDE = 11,
  U_TERRAIN_NX = 12, U_TERRAIN_NY = 13, U_RANGE0 = 16,
};
static_assert(D_TURBULENCE == 417 && D_STEP == 420 && D_ORIGIN == 421 && D_TERRAIN == 424 && D_COLLIDE == 430,
              "particle_eval.comp's slots");
static_assert(int(particles::CollisionMode::Bounce) == 1 && int(particles::CollisionMode::Kill) == 2 &&
                  int(particles::CollisionMode::Stick) == 3,
              "particle_eval.comp's C_ constants");

// The most replay steps one particle may take in the pass: a dispatch must
// end (a desktop's watchdog), and past this the CPU's cache (one frame's
// steps, not the life's) is the better path.
constexpr double kMaxGpuReplaySteps = 20000.0;

// The rate's segments as SpawnSchedule's constructor makes them (spawn.cpp),
// the same arithmetic in the same order, so the shader's inverse starts
// from the same doubles.
void segments(const particles::EmitterDesc& e, std::vector<double>& at, std::vector<double>& rate,
              std::vector<double>& cum) {
  const double a = e.start, b = e.start + e.duration;
  if (!(b > a)) return;
  at.push_back(a);
  for (const particles::CurveKey& k : e.rateKeys.keys)
    if (k.t > a && k.t < b) at.push_back(k.t);
  at.push_back(b);
  for (double t : at) rate.push_back(std::max(0.0, e.rateKeys.eval(t, e.rate)));
  cum.push_back(0.0);
  for (size_t i = 1; i < at.size(); ++i) cum.push_back(cum.back() + 0.5 * (rate[i - 1] + rate[i]) * (at[i] - at[i - 1]));
}

}  // namespace

std::vector<float> gpuTerrainHeights(const terrain::Heightfield& hf) {
  const int nx = hf.samplesX(), ny = hf.samplesY();
  std::vector<float> out(size_t(nx) * size_t(ny));
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
      out[size_t(y) * size_t(nx) + size_t(x)] = hf.isHole(x, y) ? std::numeric_limits<float>::quiet_NaN() : hf.at(x, y);
  return out;
}

bool collidesWithTerrain(const particles::Evaluator& ev, const GpuTerrainCollider* terrain) {
  if (ev.desc().collision == particles::CollisionMode::None || !terrain || !terrain->collider) return false;
  for (const particles::Collider* c : ev.inputs().colliders)
    if (c == terrain->collider) return true;
  return false;
}

bool gpuEvaluable(const particles::Evaluator& ev, double t, std::string* why, const GpuTerrainCollider* terrain) {
  const particles::EmitterDesc& e = ev.desc();
  auto no = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (e.collision != particles::CollisionMode::None)
    for (const particles::Collider* c : ev.inputs().colliders)
      if (!terrain || c != terrain->collider || !terrain->heightfield)
        return no("collision with a collider the pass does not have (a mesh's BVH, or a terrain it was not "
                  "given): replayed on the CPU");
  // The oldest candidate's age: at most the longest lifetime, and no older
  // than the emitter's first birth.
  double first = e.start;
  for (const particles::Burst& b : e.bursts) first = std::min(first, b.t);
  const double oldest = std::min(e.lifetimeMax, std::max(0.0, t - first));
  if (ev.replays() && oldest / e.replayStep > kMaxGpuReplaySteps)
    return no("more than " + std::to_string(int(kMaxGpuReplaySteps)) +
              " replay steps for its oldest particle (the CPU's cache resumes them)");
  if (e.shape == particles::Shape::Mesh || e.shape == particles::Shape::Terrain) return no("a mesh or terrain shape");
  if (!e.windKeys.empty()) return no("keyed wind");
  if (ev.movesInWorld()) return no("world space on a moving entity");
  if (ev.animatesSpawn()) return no("spawn values keyed on the timeline");
  if (e.rateKeys.keys.size() + 2 > MAX_SEGMENTS) return no("too many rate keys");
  if (e.sizeOverLife.keys.size() > MAX_KEYS || e.colourOverLife.keys.size() > MAX_KEYS) return no("too many life keys");
  if (e.bursts.size() > MAX_BURSTS) return no("too many bursts");
  const uint64_t n = ev.candidates(t);
  if (n > uint64_t(e.maxLive)) return no("more candidates than max_live (the cap chooses)");
  if (n > uint64_t(UINT32_MAX)) return no("too many candidates");
  return true;
}

GpuEmitterData gpuEmitterData(const particles::Evaluator& ev, double t, const glm::dvec3& relativeTo,
                              uint32_t packSeed, const GpuTerrainCollider* terrain) {
  const particles::EmitterDesc& e = ev.desc();
  GpuEmitterData g;
  std::vector<double>& d = g.doubles;
  d.assign(D_COUNT, 0.0);
  auto put3 = [&](size_t slot, const glm::dvec3& v) {
    for (int c = 0; c < 3; ++c) d[slot + size_t(c)] = v[c];
  };
  put3(D_OFFSET, e.origin - relativeTo);  // double, before any float (packFrame)
  d[D_T] = t;
  d[D_LIFE] = e.lifetimeMin, d[D_LIFE + 1] = e.lifetimeMax;
  d[D_SIZE] = e.sizeMin, d[D_SIZE + 1] = e.sizeMax;
  d[D_ROT] = e.rotationMinDeg, d[D_ROT + 1] = e.rotationMaxDeg;
  d[D_SPIN] = e.spinMinDegPerS, d[D_SPIN + 1] = e.spinMaxDegPerS;
  d[D_SPEED] = e.speedMin, d[D_SPEED + 1] = e.speedMax;
  put3(D_DIR, e.direction);
  d[D_SPREAD] = e.spreadDeg;
  put3(D_BOX, e.boxHalf);
  d[D_RADIUS] = e.radius;
  d[D_CONE] = e.coneAngleDeg;
  put3(D_GRAVITY, e.gravity);
  d[D_DRAG] = e.drag;
  put3(D_WIND, e.wind);
  d[D_TURBULENCE] = e.turbulence, d[D_TURBULENCE + 1] = e.turbulenceFrequency;
  d[D_TURBULENCE + 2] = e.turbulenceEvolution;
  d[D_STEP] = e.replayStep;
  put3(D_ORIGIN, e.origin);
  const bool collide = collidesWithTerrain(ev, terrain);
  if (collide) {
    const terrain::Heightfield& hf = *terrain->heightfield;
    put3(D_TERRAIN, hf.origin());
    d[D_TERRAIN + 3] = hf.spacing().x, d[D_TERRAIN + 4] = hf.spacing().y;
    d[D_TERRAIN + 5] = terrain->collider->spacing();
    d[D_COLLIDE] = e.restitution, d[D_COLLIDE + 1] = e.friction, d[D_COLLIDE + 2] = e.restSpeed;
    g.terrainHeights = terrain->heights;
  }
  std::vector<double> at, rate, cum;
  segments(e, at, rate, cum);
  for (size_t i = 0; i < at.size(); ++i) {
    d[D_SEGMENTS + i] = at[i];
    d[D_SEGMENTS + MAX_SEGMENTS + i] = rate[i];
    d[D_SEGMENTS + 2 * MAX_SEGMENTS + i] = cum[i];
  }
  for (size_t i = 0; i < e.sizeOverLife.keys.size(); ++i) {
    d[D_SIZE_KEYS + 2 * i] = e.sizeOverLife.keys[i].t;
    d[D_SIZE_KEYS + 2 * i + 1] = e.sizeOverLife.keys[i].value;
  }
  for (size_t i = 0; i < e.colourOverLife.keys.size(); ++i) {
    d[D_COLOUR_KEYS + 5 * i] = e.colourOverLife.keys[i].t;
    for (int c = 0; c < 4; ++c) d[D_COLOUR_KEYS + 5 * i + 1 + size_t(c)] = e.colourOverLife.keys[i].rgba[c];
  }

  std::vector<uint32_t>& u = g.ints;
  u.assign(U_RANGE0, 0u);
  u[U_SEED] = e.seed;
  u[U_SHAPE] = uint32_t(e.shape);
  u[U_SURFACE_ONLY] = e.surfaceOnly ? 1u : 0u;
  u[U_ALONG_NORMAL] = e.alongNormal ? 1u : 0u;
  u[U_FLIPBOOK] = uint32_t(std::max(e.flipbookFrames, 1));
  u[U_SIZE_KEYS] = uint32_t(e.sizeOverLife.keys.size());
  u[U_COLOUR_KEYS] = uint32_t(e.colourOverLife.keys.size());
  u[U_PACK_SEED] = packSeed;
  u[U_SEGMENTS] = uint32_t(at.size());
  u[U_REPLAY] = ev.replays() ? 1u : 0u;
  if (collide) {
    u[U_COLLIDE] = uint32_t(e.collision);
    u[U_TERRAIN_NX] = uint32_t(terrain->heightfield->samplesX());
    u[U_TERRAIN_NY] = uint32_t(terrain->heightfield->samplesY());
  }
  // The candidates in the CPU's order: the rate's window (t - lifetime_max, t],
  // then each burst in it (Evaluator::candidates).
  auto range = [&](uint32_t stream, uint64_t first, uint64_t count, double birth) {
    d[D_BURST_BIRTH + u[U_RANGES]] = birth;
    u.push_back(stream);
    u.push_back(uint32_t(first));
    u.push_back(uint32_t(first >> 32));
    u.push_back(uint32_t(count));
    ++u[U_RANGES];
    g.candidates += uint32_t(count);
  };
  const double window = e.lifetimeMax;
  const uint64_t first = ev.schedule().bornBy(t - window), last = ev.schedule().bornBy(t);
  range(0, first, last - first, 0.0);
  for (size_t b = 0; b < e.bursts.size(); ++b)
    if (e.bursts[b].t <= t && t - e.bursts[b].t < window) range(uint32_t(b + 1), 0, uint64_t(e.bursts[b].count), e.bursts[b].t);
  return g;
}

void dispatchGpuEvaluation(GlProgram& program, const GpuEmitterData& data, unsigned out, uint32_t first) {
  if (data.candidates == 0) return;
  gl::Buffer doubles = gl::createBuffer(), ints = gl::createBuffer();
  glNamedBufferStorage(doubles.id(), GLsizeiptr(data.doubles.size() * sizeof(double)), data.doubles.data(), 0);
  glNamedBufferStorage(ints.id(), GLsizeiptr(data.ints.size() * sizeof(uint32_t)), data.ints.data(), 0);
  // Storage bindings 0-3 are the frame's too (frame_blocks.h: the lights,
  // the objects): what was bound there is bound again after the dispatch.
  struct Bound {
    GLint buffer = 0;
    GLint64 start = 0, size = 0;
  } saved[4];
  for (GLuint i = 0; i < 4; ++i) {
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &saved[i].buffer);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &saved[i].start);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &saved[i].size);
  }
  program.use();
  program.set("uFirst", first);
  program.set("uCount", data.candidates);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, doubles.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, ints.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, out);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, data.terrainHeights);
  glDispatchCompute((data.candidates + 63) / 64, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  for (GLuint i = 0; i < 4; ++i) {
    if (saved[i].buffer != 0 && saved[i].size > 0)
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, GLuint(saved[i].buffer), GLintptr(saved[i].start),
                        GLsizeiptr(saved[i].size));
    else
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, GLuint(saved[i].buffer));
  }
}

}  // namespace hs::render

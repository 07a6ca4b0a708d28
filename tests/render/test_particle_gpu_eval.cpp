// The compute pass that evaluates emitters without replay (render/
// particle_gpu_eval.h) against the CPU reference (particles::Evaluator and
// packFrame): the same particles alive, with the same ids, variants and
// flipbook frames, and positions, velocities, sizes, colours and rotations
// within the tolerances below, for every shape it takes, rate keys,
// bursts, spread, drag and wind, at UTM coordinates and late times; and
// the emitters it must refuse.
#include <QtTest>

#include <cmath>
#include <map>

#include "particles/presets.h"
#include "render/gl/gl_handle.h"
#include "render/gl/shader_library.h"
#include "render/gl_program.h"
#include "render/offscreen_renderer.h"
#include "render/particle_gpu_eval.h"

#include <epoxy/gl.h>

using namespace hs;

namespace {

// Tolerances: the shader keeps the CPU's doubles for births, starts and
// motion, and rounds through float only inside exp, sin, cos and pow (a
// relative 1e-7..1e-6) and in the record itself (as packFrame does).
constexpr double kPositionTol = 2e-4;  // metres
constexpr double kVelocityTol = 2e-4;  // m/s
constexpr double kRelativeTol = 1e-5;  // size, colour, rotation (relative, or absolute below 1)

const glm::dvec3 kUtm(500000.0, 4400000.0, 300.0);

double relDiff(double a, double b) { return std::abs(a - b) / std::max(1.0, std::abs(b)); }

particles::EmitterDesc base(const std::string& name, particles::Shape shape) {
  particles::EmitterDesc d;
  d.name = name;
  d.seed = 99;
  d.origin = kUtm + glm::dvec3(3.0, -2.0, 1.5);
  d.shape = shape;
  d.boxHalf = {1.5, 0.5, 0.8};
  d.radius = 0.7;
  d.rate = 40.0;
  d.start = -5.0;
  d.duration = 100.0;
  d.direction = {0.2, 0.1, 1.0};
  d.spreadDeg = 25.0;
  d.speedMin = 0.5, d.speedMax = 3.0;
  d.lifetimeMin = 1.0, d.lifetimeMax = 4.0;
  d.sizeMin = 0.1, d.sizeMax = 0.4;
  d.rotationMinDeg = -180, d.rotationMaxDeg = 180;
  d.spinMinDegPerS = -90, d.spinMaxDegPerS = 90;
  d.gravity = {0, 0, -9.81};
  d.drag = 0.8;
  d.wind = {2.0, 0.5, 0.0};
  d.flipbookFrames = 16;
  d.sizeOverLife.keys = {{0.0, 0.5}, {0.4, 1.2}, {1.0, 2.0}};
  d.colourOverLife.keys = {{0.0, {4.0, 2.0, 0.5, 0.0}}, {0.2, {3.0, 1.5, 0.4, 0.9}}, {1.0, {0.2, 0.2, 0.2, 0.0}}};
  return d;
}

}  // namespace

class TestParticleGpuEval : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;
  render::GlProgram program_;

  // Every record of `desc` at t against the CPU's frame; returns the alive count.
  size_t compare(const particles::EmitterDesc& desc, double t) {
    std::string error;
    const auto ev = particles::Evaluator::create(desc, {}, error);
    if (!ev) {
      qWarning("%s", error.c_str());
      return SIZE_MAX;
    }
    std::string why;
    if (!render::gpuEvaluable(*ev, t, &why)) {
      qWarning("%s at t = %g: %s", desc.name.c_str(), t, why.c_str());
      return SIZE_MAX;
    }
    const glm::dvec3 camera = kUtm + glm::dvec3(-20.0, -35.0, 8.0);
    const particles::Frame cpu = ev->frame(t);
    const std::vector<particles::PackedParticle> ref = particles::packFrame(cpu, desc.origin, camera, desc.seed);
    const render::GpuEmitterData data = render::gpuEmitterData(*ev, t, camera, desc.seed);
    if (data.candidates != ev->candidates(t)) {
      qWarning("candidates %u, CPU %llu", data.candidates, (unsigned long long)ev->candidates(t));
      return SIZE_MAX;
    }
    std::vector<particles::PackedParticle> gpu(std::max<size_t>(data.candidates, 1));
    render::gl::Buffer out = render::gl::createBuffer();
    glNamedBufferStorage(out.id(), GLsizeiptr(gpu.size() * sizeof(particles::PackedParticle)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    render::dispatchGpuEvaluation(program_, data, out.id(), 0);
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(data.candidates * sizeof(particles::PackedParticle)), gpu.data());

    std::map<std::pair<uint32_t, uint32_t>, const particles::PackedParticle*> byId;
    for (uint32_t i = 0; i < data.candidates; ++i)
      if (gpu[i].frame != render::kGpuNotAlive) byId[{gpu[i].pad[0], gpu[i].pad[1]}] = &gpu[i];
    if (byId.size() != ref.size()) {
      qWarning("%s at t = %g: %zu alive on the GPU, %zu on the CPU", desc.name.c_str(), t, byId.size(), ref.size());
      return SIZE_MAX;
    }
    double worstX = 0, worstV = 0, worstRel = 0;
    for (size_t i = 0; i < ref.size(); ++i) {
      const particles::Particle& p = cpu.particles[i];
      const auto it = byId.find({p.id.stream, uint32_t(p.id.index)});
      if (it == byId.end()) {
        qWarning("particle (%u, %llu) missing on the GPU", p.id.stream, (unsigned long long)p.id.index);
        return SIZE_MAX;
      }
      const particles::PackedParticle &g = *it->second, &c = ref[i];
      if (g.frame != c.frame || g.variant != c.variant) {
        qWarning("particle (%u, %llu): frame %u/%u variant %u/%u", p.id.stream, (unsigned long long)p.id.index, g.frame,
                 c.frame, g.variant, c.variant);
        return SIZE_MAX;
      }
      for (int k = 0; k < 3; ++k) {
        worstX = std::max(worstX, std::abs(double(g.position[k]) - double(c.position[k])));
        worstV = std::max(worstV, std::abs(double(g.velocity[k]) - double(c.velocity[k])));
      }
      worstRel = std::max(worstRel, relDiff(g.size, c.size));
      worstRel = std::max(worstRel, relDiff(g.rotationDeg, c.rotationDeg));
      for (int k = 0; k < 4; ++k) worstRel = std::max(worstRel, relDiff(g.colour[k], c.colour[k]));
    }
    qInfo("%s at t = %g: %zu alive of %u candidates; worst |dx| %.3g m, |dv| %.3g m/s, relative %.3g",
          desc.name.c_str(), t, ref.size(), data.candidates, worstX, worstV, worstRel);
    if (worstX > kPositionTol || worstV > kVelocityTol || worstRel > kRelativeTol) return SIZE_MAX;
    return ref.size();
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    QVERIFY(r_.makeCurrent());
    QVERIFY2(program_.build({"", "", "particle_eval.comp", {}}, error), error.c_str());
  }

  // Each shape, with spread, drag, wind and the life curves, at three
  // times (0.5 s, 3 s and 500 s: births and ages far from 0 in double).
  void shapesMatchTheCpu() {
    for (auto shape : {particles::Shape::Point, particles::Shape::Box, particles::Shape::Sphere, particles::Shape::Disc,
                       particles::Shape::Cone})
      for (double t : {0.5, 3.0, 500.0}) {
        particles::EmitterDesc d = base("shape " + std::to_string(int(shape)), shape);
        d.duration = 1000.0;
        d.surfaceOnly = shape == particles::Shape::Disc;
        d.alongNormal = shape == particles::Shape::Sphere;
        const size_t n = compare(d, t);
        QVERIFY2(n != SIZE_MAX, qPrintable(QString("shape %1 at t = %2").arg(int(shape)).arg(t)));
        QVERIFY(n > 10);
      }
  }

  // Rate keys (a ramp up and down, the exact inverse of each segment),
  // bursts, no drag (the k -> 0 series), strong drag (terminal velocity).
  void rateKeysBurstsAndDrag() {
    particles::EmitterDesc d = base("keyed", particles::Shape::Box);
    d.rateKeys.keys = {{0.0, 0.0}, {1.0, 200.0}, {2.5, 30.0}, {4.0, 120.0}};
    d.bursts = {{0.7, 25}, {2.0, 40}, {9.0, 10}};
    for (double drag : {0.0, 0.8, 60.0}) {
      d.drag = drag;
      for (double t : {1.2, 3.3})
        QVERIFY2(compare(d, t) != SIZE_MAX, qPrintable(QString("drag %1 at t = %2").arg(drag).arg(t)));
    }
  }

  // The presets' emitters without replay (today the fog bank: the others
  // have turbulence or collide).
  void presetsWithoutReplay() {
    particles::PresetOptions o;
    o.at = kUtm;
    o.area = glm::dvec4(kUtm.x - 10, kUtm.y - 10, kUtm.x + 10, kUtm.y + 10);
    std::string error;
    size_t compared = 0;
    for (const char* name : {"snow", "fog", "torch", "campfire", "dust"})
      for (const particles::EmitterDesc& d : particles::makePreset(name, o, error)) {
        if (d.needsReplay()) continue;
        QVERIFY2(compare(d, 6.0) != SIZE_MAX, d.name.c_str());
        ++compared;
      }
    QVERIFY(compared >= 1);
  }

  // What the pass refuses, and why.
  void refusesWhatItCannotDo() {
    std::string error, why;
    particles::EmitterDesc d = base("turbulent", particles::Shape::Box);
    d.turbulence = 1.0;
    QVERIFY(!render::gpuEvaluable(*particles::Evaluator::create(d, {}, error), 1.0, &why));
    QVERIFY(why.find("replay") != std::string::npos);
    d = base("keyed wind", particles::Shape::Box);
    d.windKeys = {{0.0, {1, 0, 0}}, {1.0, {2, 0, 0}}};
    QVERIFY(!render::gpuEvaluable(*particles::Evaluator::create(d, {}, error), 1.0, &why));
    d = base("capped", particles::Shape::Box);
    d.maxLive = 5;
    QVERIFY(!render::gpuEvaluable(*particles::Evaluator::create(d, {}, error), 3.0, &why));
    QVERIFY(why.find("max_live") != std::string::npos);
  }
};

QTEST_MAIN(TestParticleGpuEval)
#include "test_particle_gpu_eval.moc"

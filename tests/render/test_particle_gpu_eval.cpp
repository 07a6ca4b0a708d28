// The compute pass that evaluates emitters (render/particle_gpu_eval.h)
// against the CPU reference (particles::Evaluator and packFrame): the same
// particles alive, with the same ids, variants and flipbook frames, and
// positions, velocities, sizes, colours and rotations within the
// tolerances below, for every shape it takes, rate keys, bursts, spread,
// drag and wind, turbulence's replay (weak to stiff drag, short to long
// steps, late times), at UTM coordinates; and the emitters it must refuse.
#include <QtTest>

#include <cmath>
#include <map>

#include "particles/presets.h"
#include "scene/document.h"
#include "scene/particle_world.h"
#include "scene/terrain_ops.h"
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
// With turbulence the replay's steps compound the difference (FMA
// contraction, the start's float sin/cos) through the noise's gradient.
constexpr double kReplayPositionTol = 1e-3;  // metres
constexpr double kReplayVelocityTol = 1e-3;  // m/s

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
    return compare(*ev, t);
  }

  // The same for an evaluator with its colliders (`terrain`: the one the
  // compute pass may collide with). `resting`: how many the GPU has at rest.
  size_t compare(const particles::Evaluator& evaluator, double t, const render::GpuTerrainCollider* terrain = nullptr,
                 size_t* resting = nullptr) {
    const particles::Evaluator* ev = &evaluator;
    const particles::EmitterDesc& desc = ev->desc();
    std::string why;
    if (!render::gpuEvaluable(*ev, t, &why, terrain)) {
      qWarning("%s at t = %g: %s", desc.name.c_str(), t, why.c_str());
      return SIZE_MAX;
    }
    const glm::dvec3 camera = kUtm + glm::dvec3(-20.0, -35.0, 8.0);
    const particles::Frame cpu = ev->frame(t);
    const std::vector<particles::PackedParticle> ref = particles::packFrame(cpu, desc.origin, camera, desc.seed);
    const render::GpuEmitterData data = render::gpuEmitterData(*ev, t, camera, desc.seed, terrain);
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
      if (gpu[i].frame != render::kGpuNotAlive) {
        byId[{gpu[i].pad[0], gpu[i].pad[1]}] = &gpu[i];
        if (resting && gpu[i].velocity[0] == 0.0f && gpu[i].velocity[1] == 0.0f && gpu[i].velocity[2] == 0.0f)
          ++*resting;
      }
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
    const bool replay = ev->replays();
    if (worstX > (replay ? kReplayPositionTol : kPositionTol) || worstV > (replay ? kReplayVelocityTol : kVelocityTol) ||
        worstRel > kRelativeTol)
      return SIZE_MAX;
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

  // Turbulence's replay: weak and stiff drag (k h from 0 to 6), the
  // step from 1/240 s to 1/10 s (and a remainder in every frame), strong
  // and fast noise, at 3 s and 500 s (births far from 0 in double).
  void turbulenceReplayMatchesTheCpu() {
    particles::EmitterDesc d = base("turbulent", particles::Shape::Sphere);
    d.duration = 1000.0;
    d.rate = 15.0;
    for (double drag : {0.0, 0.8, 60.0})
      for (double step : {1.0 / 240.0, 1.0 / 30.0, 0.1})
        for (double t : {3.0, 500.0}) {
          d.drag = drag;
          d.replayStep = step;
          d.turbulence = drag > 10.0 ? 40.0 : 3.0;
          d.turbulenceFrequency = 1.5;
          d.turbulenceEvolution = 0.7;
          const size_t n = compare(d, t + 0.0123);
          QVERIFY2(n != SIZE_MAX && n > 5,
                   qPrintable(QString("drag %1, step %2 at t = %3").arg(drag).arg(step).arg(t)));
        }
  }

  // Long lives under turbulence alone (no drag, no gravity): a burst of
  // sparks drifting for 30 s, 1800 steps each.
  void longTurbulentDriftMatchesTheCpu() {
    particles::EmitterDesc d = base("drifting", particles::Shape::Box);
    d.rate = 0.0;
    d.bursts = {{0.0, 25}};
    d.boxHalf = {0.5, 0.5, 0.5};
    d.speedMin = d.speedMax = 0.0;
    d.lifetimeMin = d.lifetimeMax = 1000.0;
    d.gravity = glm::dvec3(0.0);
    d.drag = 0.0;
    d.wind = glm::dvec3(0.0);
    d.turbulence = 1.0;
    QVERIFY(compare(d, 30.0) == 25);
  }

  // Every preset's emitters, turbulence replayed (no colliders given, so
  // none collides here: the scene's colliders send them to the CPU).
  void presetsMatchTheCpu() {
    particles::PresetOptions o;
    o.at = kUtm;
    o.area = glm::dvec4(kUtm.x - 10, kUtm.y - 10, kUtm.x + 10, kUtm.y + 10);
    std::string error;
    size_t compared = 0;
    for (const char* name : {"snow", "fog", "torch", "campfire", "dust"})
      for (const particles::EmitterDesc& d : particles::makePreset(name, o, error)) {
        QVERIFY2(compare(d, 6.0) != SIZE_MAX, d.name.c_str());
        ++compared;
      }
    QVERIFY(compared >= 7);
  }

  // Collisions with the terrain (scene::ParticleWorld's collider, its
  // samples uploaded as gpuTerrainHeights makes them): stick, bounce and
  // kill over hills with a hole in them, with and without turbulence, at
  // UTM coordinates, against the CPU's replay; a mesh in reach keeps the
  // emitter on the CPU.
  void terrainCollisionsMatchTheCpu() {
    scene::Document doc;
    scene::ops::NewTerrain spec;
    spec.name = "Valley";
    spec.samplesX = spec.samplesY = 65;
    spec.sizeMetres = glm::dvec2(64.0);
    spec.centre = kUtm;
    spec.start = scene::ops::NewTerrain::Start::Hills;
    spec.heightRange = {0.0f, 6.0f};
    std::string error;
    const scene::EntityId valley = scene::ops::addTerrain(doc, spec, error);
    QVERIFY2(valley != scene::kNoEntity, error.c_str());
    terrain::Heightfield& hf = scene::terrainOf(doc.state(), valley)->data->terrain().height;
    for (int y = 30; y < 36; ++y)
      for (int x = 28; x < 34; ++x) hf.setHole(x, y, true);
    scene::ParticleWorld world(doc.state());
    QVERIFY(world.terrainCollider() && world.terrainHeights());
    const std::vector<float> samples = render::gpuTerrainHeights(*world.terrainHeights());
    render::gl::Buffer heights = render::gl::createBuffer();
    glNamedBufferStorage(heights.id(), GLsizeiptr(samples.size() * sizeof(float)), samples.data(), 0);
    const render::GpuTerrainCollider terrain{world.terrainCollider(), world.terrainHeights(), heights.id()};

    particles::EmitterDesc d = base("falling", particles::Shape::Box);
    d.origin = kUtm + glm::dvec3(0.0, 0.0, 12.0);
    d.boxHalf = {12.0, 12.0, 1.0};
    d.direction = {0.3, 0.0, 1.0};
    d.lifetimeMin = 3.0, d.lifetimeMax = 6.0;
    d.drag = 0.3;
    d.replayStep = 1.0 / 30.0;
    for (auto mode : {particles::CollisionMode::Stick, particles::CollisionMode::Bounce, particles::CollisionMode::Kill})
      for (double turbulence : {0.0, 2.0}) {
        d.collision = mode;
        d.restitution = 0.6;
        d.friction = 0.2;
        d.turbulence = turbulence;
        d.turbulenceFrequency = 0.5;
        const auto ev = world.evaluator(d, error);
        QVERIFY2(ev, error.c_str());
        QCOMPARE(ev->inputs().colliders.size(), size_t(1));
        size_t resting = 0;
        const size_t n = compare(*ev, 7.3, &terrain, &resting);
        const QString what = QString("collision %1, turbulence %2").arg(int(mode)).arg(turbulence);
        QVERIFY2(n != SIZE_MAX && n > 20, qPrintable(what));
        if (mode != particles::CollisionMode::Kill) QVERIFY2(resting > 10, qPrintable(what));  // they met the ground
        // Without the terrain the pass refuses it (it would fall through).
        QVERIFY(!render::gpuEvaluable(*ev, 7.3));
      }
  }

  // What the pass refuses, and why.
  void refusesWhatItCannotDo() {
    std::string error, why;
    particles::EmitterDesc d = base("colliding", particles::Shape::Box);
    d.collision = particles::CollisionMode::Bounce;
    const particles::HeightFieldCollider ground([](double, double) { return 0.0; });
    particles::EvaluatorInputs in;
    in.colliders = {&ground};
    QVERIFY(!render::gpuEvaluable(*particles::Evaluator::create(d, in, error), 1.0, &why));
    QVERIFY(why.find("collision") != std::string::npos);
    QVERIFY(render::gpuEvaluable(*particles::Evaluator::create(d, {}, error), 1.0, &why));  // nothing to meet
    d = base("long replay", particles::Shape::Box);
    d.turbulence = 1.0;
    d.lifetimeMax = 100.0;
    d.replayStep = 1e-3;
    QVERIFY(render::gpuEvaluable(*particles::Evaluator::create(d, {}, error), 10.0, &why));  // none older than 15 s
    QVERIFY(!render::gpuEvaluable(*particles::Evaluator::create(d, {}, error), 30.0, &why));
    QVERIFY(why.find("replay steps") != std::string::npos);
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

// The GPU evaluation of particles (render/particle_gpu_eval.h,
// shaders/particle_eval.comp) against the CPU reference
// (particles::Evaluator, particles::packFrame) on a headless context: for
// every record the compute pass writes, the CPU's particle of the same
// stream and index, packed relative to the same origin. Alive or not must
// agree (but for ages within float rounding of a lifetime), and then
// position, velocity, size, colour, rotation within the stated float
// tolerances, the flipbook frame and the variant bits exactly. Emitters
// cover every shape the pass takes, spread and along-normal starts, keyed
// rates and bursts, drag from 0 to 1e6 per second (stiff: k t = 1e6 at a
// second of age) and 1e-12, an emitter at UTM coordinates seen from a
// camera beside it, and t = 3600 s. What the pass does not take (replay,
// keyed wind, a mesh shape, a capped frame) is refused with the reason.
#include <QtTest>

#include <cmath>

#include "particles/evaluate.h"
#include "particles/presets.h"
#include "render/gl/shader_library.h"
#include "render/offscreen_renderer.h"
#include "render/particle_gpu_eval.h"

using namespace hs;
using particles::EmitterDesc;

namespace {

struct Case {
  const char* name;
  EmitterDesc e;
  double t;
  glm::dvec3 relativeTo;
};

EmitterDesc base() {
  EmitterDesc e;
  e.name = "Test";
  e.seed = 77;
  e.start = -3.0;
  e.rate = 400.0;
  e.lifetimeMin = 0.5, e.lifetimeMax = 2.5;
  e.speedMin = 0.5, e.speedMax = 3.0;
  e.sizeMin = 0.05, e.sizeMax = 0.2;
  e.rotationMinDeg = -90, e.rotationMaxDeg = 90;
  e.spinMinDegPerS = -60, e.spinMaxDegPerS = 120;
  e.spreadDeg = 35.0;
  e.gravity = {0.0, 0.0, -9.81};
  e.drag = 1.5;
  e.wind = {2.0, -1.0, 0.0};
  e.flipbookFrames = 16;
  e.sizeOverLife.keys = {{0.0, 0.5}, {0.3, 1.0}, {1.0, 2.0}};
  e.colourOverLife.keys = {{0.0, {6.0, 3.0, 0.8, 0.0}}, {0.1, {6.0, 3.0, 0.8, 1.0}}, {1.0, {0.2, 0.2, 0.2, 0.0}}};
  return e;
}

std::vector<Case> cases() {
  std::vector<Case> out;
  auto add = [&](const char* name, auto change, double t = 4.0, glm::dvec3 rel = glm::dvec3(3.0, -8.0, 1.5)) {
    EmitterDesc e = base();
    change(e);
    out.push_back({name, e, t, rel});
  };
  add("point", [](EmitterDesc&) {});
  add("box", [](EmitterDesc& e) {
    e.shape = particles::Shape::Box;
    e.boxHalf = {4.0, 2.0, 0.5};
  });
  add("sphere surface along normal", [](EmitterDesc& e) {
    e.shape = particles::Shape::Sphere;
    e.surfaceOnly = true;
    e.alongNormal = true;
  });
  add("sphere volume", [](EmitterDesc& e) { e.shape = particles::Shape::Sphere; });
  add("disc", [](EmitterDesc& e) {
    e.shape = particles::Shape::Disc;
    e.direction = glm::normalize(glm::dvec3(0.3, 0.2, 1.0));
  });
  add("cone", [](EmitterDesc& e) {
    e.shape = particles::Shape::Cone;
    e.coneAngleDeg = 30.0;
    e.direction = {1.0, 0.0, 0.0};  // the other basis branch
  });
  add("keyed rate and bursts", [](EmitterDesc& e) {
    e.rateKeys.keys = {{-2.0, 0.0}, {1.0, 900.0}, {3.5, 50.0}};
    e.bursts = {{2.0, 300}, {3.9, 50}, {0.5, 40}};
  });
  add("stiff drag 1e6", [](EmitterDesc& e) { e.drag = 1e6; });
  add("drag 1e-12", [](EmitterDesc& e) { e.drag = 1e-12; });
  add("no gravity no drag", [](EmitterDesc& e) {
    e.gravity = glm::dvec3(0.0);
    e.drag = 0.0;
  });
  add("an hour in", [](EmitterDesc& e) { e.start = 0.0; }, 3600.0);
  add("at UTM", [](EmitterDesc& e) { e.origin = {500000.0, 4400000.0, 300.0}; }, 4.0,
      glm::dvec3(500003.0, 4399992.0, 301.5));
  return out;
}

}  // namespace

class TestParticleGpuEval : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;
  render::gl::ShaderLibrary shaders_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    QVERIFY(r_.makeCurrent());
  }
  void cleanupTestCase() { shaders_.release(); }

  void recordsMatchTheCpuReference_data() {
    QTest::addColumn<int>("index");
    const std::vector<Case> all = cases();
    for (size_t i = 0; i < all.size(); ++i) QTest::newRow(all[i].name) << int(i);
  }

  void recordsMatchTheCpuReference() {
    QFETCH(int, index);
    const Case c = cases()[size_t(index)];
    std::string error;
    auto ev = particles::Evaluator::create(c.e, {}, error);
    QVERIFY2(ev, error.c_str());
    std::string why;
    QVERIFY2(render::ParticleGpuEval::supports(*ev, c.t, &why), why.c_str());
    const uint64_t n = render::ParticleGpuEval::records(*ev, c.t);
    QVERIFY(n > 100);

    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferData(buffer, GLsizeiptr(n * sizeof(particles::PackedParticle)), nullptr, GL_DYNAMIC_READ);
    render::ParticleGpuEval gpu;
    QVERIFY2(gpu.evaluate(shaders_, *ev, c.t, c.relativeTo, buffer, 0, error), error.c_str());
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<particles::PackedParticle> got(n);
    glGetNamedBufferSubData(buffer, 0, GLsizeiptr(n * sizeof(particles::PackedParticle)), got.data());
    glDeleteBuffers(1, &buffer);

    // The CPU's candidates in the same order: the rate's window, then each live burst.
    std::vector<particles::ParticleId> ids;
    const uint64_t k0 = ev->schedule().bornBy(c.t - c.e.lifetimeMax), k1 = ev->schedule().bornBy(c.t);
    for (uint64_t k = k0; k < k1; ++k) ids.push_back({0, k});
    for (size_t b = 0; b < c.e.bursts.size(); ++b)
      if (c.e.bursts[b].t <= c.t && c.t - c.e.bursts[b].t < c.e.lifetimeMax)
        for (int64_t k = 0; k < c.e.bursts[b].count; ++k) ids.push_back({uint32_t(b + 1), uint64_t(k)});
    QCOMPARE(uint64_t(ids.size()), n);

    size_t alive = 0, edge = 0;
    double worstPos = 0.0, worstVel = 0.0, worstRel = 0.0;
    const double scale = glm::length(c.e.origin - c.relativeTo) + 50.0;  // metres the float positions span
    for (size_t i = 0; i < ids.size(); ++i) {
      const particles::Particle p = ev->particle(ids[i], c.t);
      particles::Frame f;
      f.particles = {p};
      const particles::PackedParticle want = particles::packFrame(f, c.e.origin, c.relativeTo, c.e.seed)[0];
      const particles::PackedParticle& g = got[i];
      const bool gpuAlive = g.size > 0.0f;
      if (gpuAlive != p.alive) {
        // Only within float rounding of the lifetime (or of the birth).
        const double margin = 1e-6 * std::max(1.0, std::abs(c.t));
        QVERIFY2(std::abs(p.age - p.lifetime) < margin || std::abs(p.age) < margin,
                 qPrintable(QString("record %1: alive %2 on the CPU, %3 here (age %4, life %5)")
                                .arg(i).arg(p.alive).arg(gpuAlive).arg(p.age).arg(p.lifetime)));
        ++edge;
        continue;
      }
      if (!p.alive) continue;
      ++alive;
      for (int k = 0; k < 3; ++k) {
        worstPos = std::max(worstPos, double(std::abs(g.position[k] - want.position[k])));
        worstVel = std::max(worstVel, double(std::abs(g.velocity[k] - want.velocity[k])) /
                                          (1.0 + std::abs(double(want.velocity[k]))));
      }
      worstRel = std::max(worstRel, double(std::abs(g.size - want.size)) / double(want.size));
      for (int k = 0; k < 4; ++k)
        worstRel = std::max(worstRel, double(std::abs(g.colour[k] - want.colour[k])) / (1.0 + std::abs(double(want.colour[k]))));
      QVERIFY2(std::abs(g.rotationDeg - want.rotationDeg) < 1e-4 * (1.0 + std::abs(double(want.rotationDeg))),
               qPrintable(QString("record %1: rotation %2, CPU %3").arg(i).arg(g.rotationDeg).arg(want.rotationDeg)));
      QVERIFY2(g.variant == want.variant, qPrintable(QString("record %1: variant bits differ").arg(i)));
      // The frame is floor(life * frames): exact but where life sits on a frame's edge.
      QVERIFY2(g.frame == want.frame || std::abs(double(g.frame) - double(want.frame)) == 1.0,
               qPrintable(QString("record %1: frame %2, CPU %3").arg(i).arg(g.frame).arg(want.frame)));
    }
    qInfo("%s: %zu records, %zu alive, %zu at a lifetime's edge; worst position %.3g m, velocity %.3g, size/colour %.3g",
          c.name, ids.size(), alive, edge, worstPos, worstVel, worstRel);
    QVERIFY(alive > 50);
    QVERIFY(edge <= 2);
    // Float: positions to 2e-7 of what they span (a float's 6e-8 times the
    // few operations of the motion; measured up to 4e-6 m over 50 m),
    // velocities and looks to 5e-6 relative (measured up to 1.1e-6).
    QVERIFY2(worstPos < 2e-7 * scale, qPrintable(QString::number(worstPos)));
    QVERIFY2(worstVel < 5e-6, qPrintable(QString::number(worstVel)));
    QVERIFY2(worstRel < 5e-6, qPrintable(QString::number(worstRel)));
  }

  void whatThePassDoesNotTakeStaysOnTheCpu() {
    std::string error, why;
    const struct {
      const char* name;
      void (*change)(EmitterDesc&);
      const char* reason;
    } refused[] = {
        {"turbulence", [](EmitterDesc& e) { e.turbulence = 1.0; }, "replay"},
        {"keyed wind", [](EmitterDesc& e) { e.windKeys = {{0.0, {1, 0, 0}}, {5.0, {0, 1, 0}}}; }, "keyed wind"},
        {"capped", [](EmitterDesc& e) { e.maxLive = 10; }, "max_live"},
    };
    for (const auto& r : refused) {
      EmitterDesc e = base();
      r.change(e);
      auto ev = particles::Evaluator::create(e, {}, error);
      QVERIFY2(ev, error.c_str());
      QVERIFY2(!render::ParticleGpuEval::supports(*ev, 4.0, &why), r.name);
      QVERIFY2(why.find(r.reason) != std::string::npos, why.c_str());
    }
  }
};

QTEST_GUILESS_MAIN(TestParticleGpuEval)
#include "test_particle_gpu_eval.moc"

// Camera paths and whole-sequence evaluation: constant speed (measured),
// passing through the points, huge coordinates, banking, look-at, and the
// purity of evaluate(sequence, t).
#include <QtTest>

#include <cmath>
#include <random>

#include "sequencer/camera_path.h"
#include "sequencer/sequence.h"

using namespace hs::sequencer;

namespace {

ScalarKey lin(double t, double v) {
  ScalarKey k;
  k.time = t;
  k.value = v;
  k.interpolation = Interpolation::Linear;
  return k;
}

// A valley fly-through: uneven spacing (8 m to 400 m), climbs and turns.
std::vector<glm::dvec3> valleyPoints(const glm::dvec3& origin = glm::dvec3(0.0)) {
  const glm::dvec3 p[] = {{0, 0, 30},     {8, 2, 31},      {60, 40, 35},   {400, 60, 80},
                          {420, 300, 90}, {300, 500, 60},  {100, 520, 40}, {90, 900, 45}};
  std::vector<glm::dvec3> out;
  for (const auto& v : p) out.push_back(origin + v);
  return out;
}

PathFollow follow(const std::vector<glm::dvec3>& points, double duration) {
  PathFollow f;
  f.path.points = points;
  f.progress.keys = {lin(0.0, 0.0), lin(duration, 1.0)};
  return f;
}

// Largest relative deviation of the sampled speed from length / duration.
double speedDeviation(const std::function<glm::dvec3(double)>& position, double duration, double length, int samples) {
  const double expected = length / duration, dt = duration / samples;
  double worst = 0.0;
  glm::dvec3 prev = position(0.0);
  for (int i = 1; i <= samples; ++i) {
    const glm::dvec3 p = position(i * dt);
    worst = std::max(worst, std::abs(glm::length(p - prev) / dt / expected - 1.0));
    prev = p;
  }
  return worst;
}

}  // namespace

class TestPath : public QObject {
  Q_OBJECT

 private slots:
  void constantSpeedWithinHalfAPercent() {
    const auto points = valleyPoints();
    const PathSampler sampler(points);
    const PathFollow f = follow(points, 60.0);
    const int samples = 60 * 60 * 4;  // 4 samples per frame at 60 fps
    const double dev = speedDeviation([&](double t) { return evaluatePath(f, sampler, t).position; }, 60.0,
                                      sampler.length(), samples);
    // The same path travelled by the spline's own (chord-length) parameter,
    // which is what a naive implementation would do.
    const double naive = speedDeviation(
        [&](double t) { return sampler.positionAtParameter(t / 60.0 * sampler.parameterLength()); }, 60.0,
        sampler.length(), samples);
    qInfo("path length %.3f m; speed deviation from constant: arc-length %.2e (budget 5e-3), naive parameter %.2e",
          sampler.length(), dev, naive);
    QVERIFY(dev < 0.005);
    QVERIFY(dev < 1e-5);      // in fact far inside the budget
    QVERIFY(naive > 0.005);   // and the test would catch the naive way
  }

  void passesThroughItsPoints() {
    const auto points = valleyPoints();
    const PathSampler sampler(points);
    // Each point is on the curve: the nearest sample is within a millimetre.
    for (const glm::dvec3& p : points) {
      double best = 1e300;
      for (int i = 0; i <= 20000; ++i) best = std::min(best, glm::length(sampler.position(sampler.length() * i / 20000.0) - p));
      QVERIFY2(best < 0.05, qPrintable(QString("point missed by %1 m").arg(best)));
    }
    QVERIFY(glm::length(sampler.position(0.0) - points.front()) < 1e-9);
    QVERIFY(glm::length(sampler.position(sampler.length()) - points.back()) < 1e-9);
    QVERIFY(glm::length(sampler.position(-5.0) - points.front()) < 1e-9);  // clamped
  }

  // The box (the spans' Bézier hulls) holds every point of the curve,
  // where it overshoots its points too, and is tight: each face touched
  // within 15 % of the box's size by the curve (brute force, 20,000
  // samples); at UTM coordinates the same box shifted; a point's box is it.
  void boxHoldsTheCurve() {
    const glm::dvec3 utm(512345.0, 4412345.0, 0.0);
    for (const glm::dvec3& origin : {glm::dvec3(0.0), utm}) {
      const auto points = valleyPoints(origin);
      const PathSampler sampler(points);
      const auto [lo, hi] = sampler.box();
      glm::dvec3 seenLo(1e300), seenHi(-1e300), pointsLo(1e300), pointsHi(-1e300);
      for (const glm::dvec3& p : points) pointsLo = glm::min(pointsLo, p), pointsHi = glm::max(pointsHi, p);
      for (int i = 0; i <= 20000; ++i) {
        const glm::dvec3 p = sampler.position(sampler.length() * i / 20000.0);
        QVERIFY2(glm::all(glm::lessThanEqual(lo - 1e-6, p)) && glm::all(glm::lessThanEqual(p, hi + 1e-6)),
                 qPrintable(QString("sample %1 outside the box").arg(i)));
        seenLo = glm::min(seenLo, p), seenHi = glm::max(seenHi, p);
      }
      const glm::dvec3 size = hi - lo;
      for (int k = 0; k < 3; ++k)
        if (size[k] > 1.0) QVERIFY(seenLo[k] - lo[k] < 0.15 * size[k] && hi[k] - seenHi[k] < 0.15 * size[k]);
      auto largest = [](const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); };
      if (origin == glm::dvec3(0.0))
        qInfo("the curve overshoots its points' box by up to %.2f m; the box holds it with at most %.2f m to spare",
              std::max(largest(pointsLo - seenLo), largest(seenHi - pointsHi)),
              std::max(largest(seenLo - lo), largest(hi - seenHi)));
    }
    const auto [a, b] = PathSampler({{1, 2, 3}}).box();
    QVERIFY(a == glm::dvec3(1, 2, 3) && b == a);
  }

  void hugeCoordinatesLoseNothing() {
    const glm::dvec3 utm(512345.0, 4412345.0, 0.0);
    const PathSampler local(valleyPoints()), far(valleyPoints(utm));
    QVERIFY(std::abs(local.length() - far.length()) < 1e-6);
    double worst = 0.0;
    for (int i = 0; i <= 1000; ++i) {
      const double s = local.length() * i / 1000.0;
      worst = std::max(worst, glm::length((far.position(s) - utm) - local.position(s)));
    }
    qInfo("largest difference at UTM coordinates: %.3g m", worst);
    QVERIFY(worst < 1e-6);
  }

  void degeneratePaths() {
    const PathSampler empty(std::vector<glm::dvec3>{});
    QVERIFY(empty.empty());
    const PathSampler one({{1, 2, 3}});
    QCOMPARE(one.length(), 0.0);
    QVERIFY(one.position(10.0) == glm::dvec3(1, 2, 3));
    const PathSampler dup({{0, 0, 0}, {0, 0, 0}, {10, 0, 0}, {10, 0, 0}});
    QVERIFY(std::abs(dup.length() - 10.0) < 1e-9);
    QVERIFY(std::isfinite(dup.position(5.0).x));
  }

  void aimsAlongThePathOrAtATarget() {
    const auto points = valleyPoints();
    const PathSampler sampler(points);
    PathFollow f = follow(points, 60.0);
    const PathPose along = evaluatePath(f, sampler, 20.0);
    const glm::dvec3 fwd = along.orientation * glm::dvec3(0, 0, -1);
    const double s = 20.0 / 60.0 * sampler.length();
    QVERIFY(glm::length(fwd - sampler.tangent(s)) < 1e-9);
    // Camera up stays on the upper side (no roll without banking).
    QVERIFY(std::abs((along.orientation * glm::dvec3(1, 0, 0)).z) < 1e-12);  // right stays level
    f.aim = PathAim::Point;
    f.targetPoint = {250, 250, 0};
    const PathPose at = evaluatePath(f, sampler, 33.0);
    const glm::dvec3 look = at.orientation * glm::dvec3(0, 0, -1);
    QVERIFY(glm::length(look - glm::normalize(f.targetPoint - at.position)) < 1e-12);
  }

  void banksIntoTurnsWithinItsLimit() {
    // A circle of radius 200 m turning left (counter-clockwise seen from above).
    std::vector<glm::dvec3> circle;
    for (int i = 0; i <= 24; ++i) {
      const double a = glm::radians(15.0 * i);
      circle.push_back({200.0 * std::cos(a), 200.0 * std::sin(a), 50.0});
    }
    const PathSampler sampler(circle);
    PathFollow f = follow(circle, 60.0);  // ~1257 m in 60 s: 21 m/s
    f.bank = true;
    f.maxBankDeg = 30.0;
    const PathPose p = evaluatePath(f, sampler, 30.0);
    const double v = sampler.length() / 60.0;
    const double expected = glm::degrees(std::atan(v * v / 200.0 / 9.80665));
    qInfo("speed %.1f m/s on a 200 m circle: bank %.2f deg (coordinated turn %.2f deg)", p.speed, p.bankDeg, expected);
    QVERIFY(std::abs(p.speed - v) < 1e-6 * v);
    QVERIFY(p.bankDeg > 0.0);
    QVERIFY(std::abs(p.bankDeg - 30.0 * std::tanh(expected / 30.0)) < 0.3);
    // Into a left turn the right side of the frame rises.
    QVERIFY((p.orientation * glm::dvec3(1, 0, 0)).z > 0.0);
    // Faster: the limit holds.
    f.progress.keys = {lin(0.0, 0.0), lin(10.0, 1.0)};
    const PathPose fast = evaluatePath(f, sampler, 5.0);
    QVERIFY(fast.bankDeg > 25.0 && fast.bankDeg < 30.0);
    // A straight path does not bank.
    const PathSampler line({{0, 0, 0}, {100, 0, 0}, {200, 0, 0}});
    PathFollow straight = follow({{0, 0, 0}, {100, 0, 0}, {200, 0, 0}}, 10.0);
    straight.bank = true;
    QVERIFY(std::abs(evaluatePath(straight, line, 5.0).bankDeg) < 1e-9);
  }

  void evaluationIsPure() {
    // Frames evaluated in any order, any number of times, give the same
    // values bit for bit (DESIGN.md, "Time and determinism").
    Sequence seq;
    Binding cam;
    cam.entity = 1;
    cam.label = "Camera";
    ScalarTrack fov{"camera.fov_deg", {lin(0, 60), lin(30, 35)}};
    fov.keys[1].interpolation = Interpolation::Cubic;
    fov.keys.push_back(lin(60, 50));
    cam.tracks.push_back(fov);
    cam.tracks.push_back(StepTrack{"entity.visible", {{0.0, true}, {12.5, false}, {40.0, true}}});
    PathFollow f = follow(valleyPoints(), 60.0);
    f.aim = PathAim::Entity;
    f.targetEntity = 2;
    f.bank = true;
    cam.path = f;
    Binding target;
    target.entity = 2;
    target.label = "Pillar";
    VectorTrack pos{"transform.translation", {}};
    VectorKey a, b;
    a.time = 0;
    a.value = {300, 300, 0};
    b.time = 60;
    b.value = {350, 600, 20};
    pos.keys = {a, b};
    target.tracks.push_back(pos);
    seq.bindings = {cam, target};
    const CompiledSequence compiled(seq);
    QVERIFY(compiled.problems().empty());

    std::vector<SequenceState> forward;
    for (int64_t f2 = 0; f2 < 3600; f2 += 7) forward.push_back(evaluateFrame(compiled, f2));
    std::vector<int64_t> order;
    for (int64_t f2 = 0; f2 < 3600; f2 += 7) order.push_back(f2);
    std::mt19937 rng(1);
    std::shuffle(order.begin(), order.end(), rng);
    for (int64_t f2 : order) {
      const SequenceState s = evaluateFrame(compiled, f2);
      const SequenceState& ref = forward[size_t(f2 / 7)];
      QCOMPARE(s.values.size(), ref.values.size());
      for (size_t i = 0; i < s.values.size(); ++i) QVERIFY(s.values[i].value == ref.values[i].value);
    }
    // The camera aims at the animated target.
    const SequenceState s = evaluate(compiled, 30.0);
    QVERIFY(s.warnings.empty());
    const glm::dvec3 camPos = *s.vector(1, "transform.translation");
    const glm::dvec3 tgt = *s.vector(2, "transform.translation");
    const glm::dvec3 look = *s.rotation(1, "transform.rotation") * glm::dvec3(0, 0, -1);
    QVERIFY(glm::dot(look, glm::normalize(tgt - camPos)) > std::cos(glm::radians(31.0)));  // bank rolls, aim holds
    QCOMPARE(*s.flag(1, "entity.visible"), false);
    // An unknown target falls back to the path with a warning.
    seq.bindings[0].path->targetEntity = 99;
    const SequenceState lost = evaluate(seq, 30.0);
    QCOMPARE(lost.warnings.size(), size_t(1));
  }

  void compileReportsProblems() {
    Sequence seq;
    Binding b;
    b.entity = 5;
    b.label = "Cam";
    ScalarTrack t{"camera.fov_deg", {lin(2, 1), lin(1, 2)}};
    b.tracks.push_back(t);
    RotationTrack r{"transform.rotation", {}};
    RotationKey k;
    k.value = glm::dquat(2, 0, 0, 0);
    r.keys.push_back(k);
    b.tracks.push_back(r);
    seq.bindings.push_back(b);
    const CompiledSequence c(seq);
    QCOMPARE(c.problems().size(), size_t(2));
    // Sorted and normalized anyway: evaluation works.
    QCOMPARE(*evaluate(std::get<ScalarTrack>(c.sequence().bindings[0].tracks[0]), 1.5), 1.5);
    QVERIFY(std::abs(glm::length(*evaluate(std::get<RotationTrack>(c.sequence().bindings[0].tracks[1]), 0.0)) - 1.0) < 1e-15);
  }
};

QTEST_APPLESS_MAIN(TestPath)
#include "test_sequencer_path.moc"

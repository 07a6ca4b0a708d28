// Tracks and keys: interpolation exact at keys, clamped cubics that never
// overshoot, eases, user and broken tangents, one key, coincident keys,
// keys at huge times, quaternion shortest paths through 179/180/181 degrees,
// enclosures of a track's values over a window,
// JSON round trips, frame ranges and output names.
#include <QtTest>

#include <cmath>
#include <random>

#include "sequencer/interpolation.h"
#include "sequencer/output_pattern.h"
#include "sequencer/sequence_json.h"
#include "sequencer/track.h"

using namespace hs::sequencer;

namespace {

glm::dquat yaw(double degrees) { return glm::angleAxis(glm::radians(degrees), glm::dvec3(0, 0, 1)); }

// Signed yaw angle (degrees) of a rotation about +Z.
double yawOf(const glm::dquat& q) {
  const glm::dvec3 x = q * glm::dvec3(1, 0, 0);
  return glm::degrees(std::atan2(x.y, x.x));
}

ScalarKey key(double t, double v, Interpolation i = Interpolation::Cubic, Ease e = Ease::None) {
  ScalarKey k;
  k.time = t;
  k.value = v;
  k.interpolation = i;
  k.ease = e;
  return k;
}

RotationKey rkey(double t, const glm::dquat& q, Interpolation i = Interpolation::Linear) {
  RotationKey k;
  k.time = t;
  k.value = q;
  k.interpolation = i;
  return k;
}

}  // namespace

class TestTracks : public QObject {
  Q_OBJECT

 private slots:
  void easesAreDefinedAsDocumented() {
    for (Ease e : {Ease::None, Ease::In, Ease::Out, Ease::InOut}) {
      QCOMPARE(easeValue(e, 0.0), 0.0);
      QCOMPARE(easeValue(e, 1.0), 1.0);
      double prev = 0.0;
      for (int i = 1; i <= 1000; ++i) {
        const double u = i / 1000.0, v = easeValue(e, u);
        QVERIFY2(v >= prev, "eases are monotone");
        prev = v;
        // The slope is the derivative of the value.
        const double d = (easeValue(e, std::min(1.0, u + 1e-6)) - easeValue(e, u - 1e-6)) / (std::min(1.0, u + 1e-6) - (u - 1e-6));
        QVERIFY(std::abs(d - easeSlope(e, u)) < 1e-4);
      }
    }
    QCOMPARE(easeSlope(Ease::In, 0.0), 0.0);
    QCOMPARE(easeSlope(Ease::In, 1.0), 1.0);
    QCOMPARE(easeSlope(Ease::Out, 0.0), 1.0);
    QCOMPARE(easeSlope(Ease::Out, 1.0), 0.0);
    QCOMPARE(easeSlope(Ease::InOut, 0.0), 0.0);
    QCOMPARE(easeSlope(Ease::InOut, 1.0), 0.0);
    QCOMPARE(easeValue(Ease::InOut, 0.5), 0.5);
  }

  void exactAtKeys() {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> val(-1e3, 1e3), gap(0.001, 10.0);
    for (int trial = 0; trial < 200; ++trial) {
      ScalarTrack tr{"camera.fov_deg", {}};
      VectorTrack vt{"transform.translation", {}};
      double t = val(rng);
      for (int i = 0; i < 12; ++i) {
        ScalarKey k = key(t, val(rng), Interpolation(rng() % 3), Ease(rng() % 4));
        k.tangentMode = TangentMode(rng() % 3);
        k.inSlope = val(rng);
        k.outSlope = val(rng);
        tr.keys.push_back(k);
        VectorKey vk;
        vk.time = t;
        vk.value = {val(rng), val(rng), val(rng)};
        vk.interpolation = k.interpolation;
        vt.keys.push_back(vk);
        t += gap(rng);
      }
      for (size_t i = 0; i < tr.keys.size(); ++i) {
        QCOMPARE(*evaluate(tr, tr.keys[i].time), tr.keys[i].value);  // bit for bit
        QVERIFY(*evaluate(vt, vt.keys[i].time) == vt.keys[i].value);
      }
    }
  }

  void clampedCubicNeverLeavesItsKeys() {
    // Random values at random (uneven) times, auto tangents: every sample of
    // a segment lies between its two keys.
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> val(-100.0, 100.0), gap(0.01, 5.0), coin(0.0, 1.0);
    double worst = 0.0;
    for (int trial = 0; trial < 300; ++trial) {
      ScalarTrack tr{"x", {}};
      double t = 0.0;
      const int n = 2 + int(rng() % 14);
      for (int i = 0; i < n; ++i) {
        // Some plateaus and repeated values: the classic overshoot cases.
        const double v = (i > 0 && coin(rng) < 0.2) ? tr.keys.back().value : val(rng);
        tr.keys.push_back(key(t, v, Interpolation::Cubic, coin(rng) < 0.3 ? Ease(rng() % 4) : Ease::None));
        t += coin(rng) < 0.1 ? gap(rng) * 100.0 : gap(rng);  // very uneven spacing too
      }
      for (size_t i = 0; i + 1 < tr.keys.size(); ++i) {
        const double lo = std::min(tr.keys[i].value, tr.keys[i + 1].value);
        const double hi = std::max(tr.keys[i].value, tr.keys[i + 1].value);
        for (int s = 0; s <= 400; ++s) {
          const double tt = tr.keys[i].time + (tr.keys[i + 1].time - tr.keys[i].time) * s / 400.0;
          const double v = *evaluate(tr, tt);
          worst = std::max(worst, std::max(lo - v, v - hi));
          QVERIFY2(v >= lo - 1e-12 && v <= hi + 1e-12, qPrintable(QString("overshoot %1 outside [%2, %3]").arg(v).arg(lo).arg(hi)));
        }
      }
    }
    qInfo("largest excursion past a neighbouring key: %.3g (0 = none)", std::max(0.0, worst));
  }

  void autoTangentsAreSmoothAndFlatAtExtremes() {
    ScalarTrack tr{"x", {key(0, 0), key(1, 10), key(2, 5), key(4, 6)}};
    // Key 1 is a maximum: flat there.
    QCOMPARE(evaluateWithSlope(tr, 1.0)->slope, 0.0);
    // Ends are flat (Blender's auto clamped).
    QCOMPARE(evaluateWithSlope(tr, 0.0)->slope, 0.0);
    // Key 2 sits between 10 and 6 (decreasing then increasing? 10 -> 5 -> 6 is a minimum): flat.
    QCOMPARE(evaluateWithSlope(tr, 2.0)->slope, 0.0);
    // C1 across a key that is not an extreme.
    ScalarTrack mono{"x", {key(0, 0), key(1, 1), key(3, 4), key(4, 10)}};
    const double left = evaluateWithSlope(mono, 1.0 - 1e-9)->slope, right = evaluateWithSlope(mono, 1.0)->slope;
    QVERIFY(std::abs(left - right) < 1e-6);
    QVERIFY(right > 0.0);
  }

  void userAndBrokenTangents() {
    ScalarTrack tr{"x", {key(0, 0), key(1, 1), key(2, 0)}};
    tr.keys[1].setSlope(2.5);
    const double h = 1e-7;
    QVERIFY(std::abs(evaluateWithSlope(tr, 1.0 - h)->slope - 2.5) < 1e-4);
    QVERIFY(std::abs(evaluateWithSlope(tr, 1.0)->slope - 2.5) < 1e-9);
    tr.keys[1].tangentMode = TangentMode::Broken;
    tr.keys[1].inSlope = -3.0;
    tr.keys[1].outSlope = 4.0;
    QVERIFY(std::abs(evaluateWithSlope(tr, 1.0 - h)->slope - (-3.0)) < 1e-4);
    QVERIFY(std::abs(evaluateWithSlope(tr, 1.0)->slope - 4.0) < 1e-9);
    QCOMPARE(*evaluate(tr, 1.0), 1.0);
    // User mode ignores inSlope (one slope, both sides).
    tr.keys[1].tangentMode = TangentMode::User;
    QVERIFY(std::abs(evaluateWithSlope(tr, 1.0 - h)->slope - 4.0) < 1e-4);
  }

  void linearConstantAndEasedSegments() {
    ScalarTrack tr{"x", {key(0, 0, Interpolation::Linear), key(2, 10, Interpolation::Constant), key(3, 20)}};
    QCOMPARE(*evaluate(tr, 1.0), 5.0);
    QCOMPARE(*evaluate(tr, 2.5), 10.0);  // constant holds until the next key
    QCOMPARE(*evaluate(tr, 3.0), 20.0);
    QCOMPARE(*evaluate(tr, 99.0), 20.0);  // holds after the last key
    QCOMPARE(*evaluate(tr, -5.0), 0.0);   // and before the first
    tr.keys[0].ease = Ease::InOut;
    QCOMPARE(*evaluate(tr, 1.0), 5.0);
    QCOMPARE(evaluateWithSlope(tr, 0.0)->slope, 0.0);
    QVERIFY(*evaluate(tr, 0.5) < 2.5);  // slow start
  }

  void oneKeyAndNoKeys() {
    ScalarTrack none{"x", {}};
    QVERIFY(!evaluate(none, 0.0));
    ScalarTrack one{"x", {key(5, 3.25)}};
    for (double t : {-1e9, 0.0, 5.0, 5.0 + 1e-12, 1e9}) {
      QCOMPARE(*evaluate(one, t), 3.25);
      QCOMPARE(evaluateWithSlope(one, t)->slope, 0.0);
    }
    RotationTrack r1{"transform.rotation", {rkey(1, yaw(30))}};
    QVERIFY(std::abs(yawOf(*evaluate(r1, 100.0)) - 30.0) < 1e-12);
    StepTrack s1{"entity.visible", {{3.0, false}}};
    QCOMPARE(*evaluate(s1, 0.0), false);
  }

  void coincidentKeysMakeAJump() {
    ScalarTrack tr{"x", {key(0, 0), key(1, 1), key(1, 5), key(1, 7), key(2, 5)}};
    QCOMPARE(*evaluate(tr, 1.0), 7.0);  // the last key at that time holds
    QVERIFY(std::abs(*evaluate(tr, 1.0 - 1e-9) - 1.0) < 1e-6);  // approached from the left: the first
    for (int i = 0; i <= 2000; ++i) {
      const double t = -0.5 + 3.0 * i / 2000.0;
      const auto s = evaluateWithSlope(tr, t);
      QVERIFY(std::isfinite(s->value) && std::isfinite(s->slope));
    }
    // Both sides of the jump are flat (their pieces end there).
    QCOMPARE(evaluateWithSlope(tr, 1.0)->slope, 0.0);
    // Rotations and vectors alike.
    RotationTrack r{"transform.rotation", {rkey(0, yaw(0), Interpolation::Cubic), rkey(1, yaw(10), Interpolation::Cubic),
                                           rkey(1, yaw(50), Interpolation::Cubic), rkey(2, yaw(60), Interpolation::Cubic)}};
    QVERIFY(std::abs(yawOf(*evaluate(r, 1.0)) - 50.0) < 1e-9);
    QVERIFY(std::abs(yawOf(*evaluate(r, 1.0 - 1e-9)) - 10.0) < 1e-6);
    StepTrack s{"entity.visible", {{0.0, true}, {1.0, false}, {1.0, true}}};
    QCOMPARE(*evaluate(s, 1.0), true);
    QCOMPARE(*evaluate(s, 0.999), true);
  }

  void keysAtHugeTimes() {
    // t = 1e6 s (11.6 days): double time and the relative segment parameter
    // keep the same precision as near t = 0.
    const FrameRate rate{60, 1};
    QCOMPARE(frameTime(60000000, rate), 1e6);
    QCOMPARE(frameTime(60000001, rate) - 1e6, 1.0 / 60.0 + (frameTime(60000001, rate) - 1e6 - 1.0 / 60.0));
    const double base = 1e6;
    ScalarTrack nearZero{"x", {}}, huge{"x", {}};
    const double times[] = {0.0, 1.0 / 60.0, 2.0 / 60.0, 0.5, 3.0};
    const double values[] = {0.0, 1.0, -2.0, 4.0, 4.5};
    for (int i = 0; i < 5; ++i) {
      nearZero.keys.push_back(key(times[i], values[i]));
      huge.keys.push_back(key(base + times[i], values[i]));
    }
    for (int i = 0; i < 5; ++i) QCOMPARE(*evaluate(huge, base + times[i]), values[i]);
    double worst = 0.0;
    for (int64_t f = 0; f <= 180; ++f) {
      const double a = *evaluate(nearZero, frameTime(f, rate));
      const double b = *evaluate(huge, frameTime(f + 60000000, rate));
      worst = std::max(worst, std::abs(a - b));
    }
    qInfo("largest difference between keys near 0 and near 1e6 s: %.3g", worst);
    QVERIFY(worst < 1e-7);
    // Distinct frames stay distinct: no two frames at 1e6 s collapse onto one time.
    QVERIFY(frameTime(60000001, rate) > frameTime(60000000, rate));
    QCOMPARE(frameAtTime(frameTime(60000123, rate), rate), int64_t(60000123));
  }

  // valueRange encloses every value of the track over a window (dense
  // samples, 1e-12 of the values' scale), with user slopes that overshoot,
  // eases, jumps, constant and linear pieces and windows that start before
  // the first key or end after the last; for linear and constant tracks it
  // is the exact range. turnsDuring says a rotation is still only where it is.
  void valueRangeEnclosesTheTrack() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    size_t windows = 0;
    double slack = 0.0;  // how much wider than the samples' range, as a share of it
    for (int trial = 0; trial < 300; ++trial) {
      ScalarTrack track;
      double t = 0.0;
      const bool straight = trial % 3 == 0;  // linear and constant only: the range is exact
      for (int k = 0; k < 6; ++k) {
        const Interpolation kinds[] = {Interpolation::Cubic, Interpolation::Linear, Interpolation::Constant};
        ScalarKey key0 = key(t, 5.0 * u(rng), straight ? kinds[1 + (trial + k) % 2] : kinds[(trial + k) % 3],
                             Ease((trial + k) % 4));
        if (!straight && k % 2 == 1) key0.setSlope(40.0 * u(rng));  // steep user slopes overshoot
        track.keys.push_back(key0);
        if (trial % 5 == 0 && k == 2) continue;  // a jump: the next key at the same time
        t += 0.2 + std::abs(u(rng));
      }
      const double end = track.keys.back().time;
      for (int w = 0; w < 5; ++w) {
        double t0 = -0.5 + (end + 1.0) * (0.5 + 0.5 * u(rng)), t1 = t0 + (end + 1.0) * 0.3 * (1.0 + u(rng));
        const auto r = valueRange(track, t0, t1);
        QVERIFY(r && r->first <= r->second);
        double lo = 1e300, hi = -1e300;
        for (int i = 0; i <= 4000; ++i) {
          const double v = *evaluate(track, t0 + (t1 - t0) * i / 4000.0);
          lo = std::min(lo, v), hi = std::max(hi, v);
        }
        for (const ScalarKey& k : track.keys)
          if (k.time >= t0 && k.time <= t1) lo = std::min(lo, k.value), hi = std::max(hi, k.value);
        QVERIFY2(r->first <= lo + 1e-12 && r->second >= hi - 1e-12, qPrintable(QString("trial %1").arg(trial)));
        if (straight) {
          // Exact: the sampled range reaches the enclosure (a linear extreme is at a key or an end).
          QVERIFY(std::abs(r->first - lo) < 1e-12 && std::abs(r->second - hi) < 1e-12);
        } else if (hi > lo) {
          slack = std::max(slack, ((r->second - r->first) - (hi - lo)) / (hi - lo));
        }
        ++windows;
      }
    }
    qInfo("%zu windows enclosed; a cubic's polygon at most %.2fx wider than the samples' range", windows, 1.0 + slack);
    QVERIFY(slack < 2.0);
    // A short window on a long segment (a lifetime's worth of a minute-long
    // move): the piece's polygon, not the segment's, so about the piece's range.
    ScalarTrack slow;
    slow.keys = {key(0.0, 0.0), key(60.0, 100.0)};
    const auto piece = valueRange(slow, 30.0, 32.0);
    const double p0 = *evaluate(slow, 30.0), p1 = *evaluate(slow, 32.0);
    qInfo("2 s of a 60 s ease: range %.6f..%.6f, the curve %.6f..%.6f", piece->first, piece->second, p0, p1);
    QVERIFY(piece->first <= p0 && piece->second >= p1 && (piece->second - piece->first) < 1.01 * (p1 - p0));
    // Vector tracks: each component apart.
    VectorTrack v;
    v.property = "transform.translation";
    VectorKey a, b;
    a.time = 0.0, a.value = {0, 5, -1}, a.interpolation = Interpolation::Linear;
    b.time = 2.0, b.value = {4, 1, -1};
    v.keys = {a, b};
    const auto vr = valueRange(v, 0.5, 1.0);
    QVERIFY(vr);
    QVERIFY(glm::length(vr->first - glm::dvec3(1, 3, -1)) < 1e-12 && glm::length(vr->second - glm::dvec3(2, 4, -1)) < 1e-12);
    QVERIFY(!valueRange(ScalarTrack{}, 0.0, 1.0));

    // Rotations: still before the first key, between equal keys and after
    // the last; turning where the keys differ or a still pair has a spin.
    RotationTrack r;
    r.keys = {rkey(1.0, yaw(0)), rkey(2.0, yaw(0)), rkey(3.0, yaw(90)), rkey(4.0, yaw(90), Interpolation::Cubic)};
    QVERIFY(!turnsDuring(r, -5.0, 1.0));
    QVERIFY(!turnsDuring(r, 1.0, 2.0));
    QVERIFY(turnsDuring(r, 1.5, 2.5));
    QVERIFY(turnsDuring(r, 2.9, 3.1));
    QVERIFY(!turnsDuring(r, 4.0, 9.0));
    r.keys[0].interpolation = Interpolation::Cubic;
    r.keys[0].setSlope({0, 0, 2.0});  // leaves yaw 0 spinning, comes back to it
    QVERIFY(turnsDuring(r, 1.2, 1.4));
    QVERIFY(!turnsDuring(RotationTrack{}, 0.0, 1.0));
  }

  void quaternionsTakeTheShortWay() {
    // 0 -> 179: the long-looking way is the short one (+179).
    RotationTrack a{"transform.rotation", {rkey(0, yaw(0)), rkey(1, yaw(179))}};
    QVERIFY(std::abs(yawOf(*evaluate(a, 0.5)) - 89.5) < 1e-9);
    // 0 -> 181 = -179: the short way is negative.
    RotationTrack b{"transform.rotation", {rkey(0, yaw(0)), rkey(1, yaw(181))}};
    QVERIFY(std::abs(yawOf(*evaluate(b, 0.5)) + 89.5) < 1e-9);
    // 179 -> 181 crosses 180 and moves 2 degrees, never 358.
    RotationTrack c{"transform.rotation", {rkey(0, yaw(179)), rkey(1, yaw(181))}};
    glm::dquat prev = *evaluate(c, 0.0);
    for (int i = 1; i <= 100; ++i) {
      const glm::dquat q = *evaluate(c, i / 100.0);
      QVERIFY(glm::degrees(rotationAngleBetween(prev, q)) < 0.0201);
      prev = q;
    }
    QVERIFY(std::abs(std::abs(yawOf(*evaluate(c, 0.5))) - 180.0) < 1e-9);
    // The stored sign of a quaternion never changes the path.
    RotationTrack d{"transform.rotation", {rkey(0, -yaw(0)), rkey(1, yaw(181))}};
    QVERIFY(std::abs(yawOf(*evaluate(d, 0.5)) + 89.5) < 1e-9);
    // Cubic too.
    RotationTrack e{"transform.rotation", {rkey(0, yaw(0), Interpolation::Cubic), rkey(1, yaw(181), Interpolation::Cubic)}};
    QVERIFY(yawOf(*evaluate(e, 0.5)) < -80.0);
  }

  void halfTurnIsStable() {
    // Exactly 180 degrees (and within rounding of it): the documented
    // direction, counter-clockwise about +Z, whatever the quaternion signs
    // and rounding noise.
    const glm::dquat exact(0.0, 0.0, 0.0, 1.0);  // 180 about Z, w exactly 0
    const glm::dquat variants[] = {exact, -exact, yaw(180.0), -yaw(180.0), yaw(180.0 + 1e-8), yaw(180.0 - 1e-8),
                                   yaw(-180.0)};
    for (const glm::dquat& target : variants)
      for (const glm::dquat& start : {yaw(0), -yaw(0)}) {
        RotationTrack t{"transform.rotation", {rkey(0, start), rkey(1, target)}};
        const double mid = yawOf(*evaluate(t, 0.5));
        QVERIFY2(std::abs(mid - 90.0) < 1e-5, qPrintable(QString("half turn went %1").arg(mid)));
      }
    // The rule is about the world axis, so it holds for any start orientation.
    const glm::dquat start = yaw(37.0);
    RotationTrack t{"transform.rotation", {rkey(0, start), rkey(1, yaw(37.0 + 180.0))}};
    QVERIFY(std::abs(yawOf(*evaluate(t, 0.5)) - (37.0 + 90.0)) < 1e-6);
    // Pitch half turn (axis X): positive about +X.
    const glm::dquat pitch180 = glm::angleAxis(glm::pi<double>(), glm::dvec3(1, 0, 0));
    RotationTrack p{"transform.rotation", {rkey(0, glm::dquat(1, 0, 0, 0)), rkey(1, -pitch180)}};
    const glm::dvec3 up = *evaluate(p, 0.5) * glm::dvec3(0, 1, 0);
    QVERIFY(std::abs(up.z - 1.0) < 1e-9);  // +90 about +X takes +Y to +Z
  }

  void continuousSpinNeverFlips() {
    // Yaw keys every 90 degrees for three turns, cubic: the orientation
    // moves forward in small steps, no jump back at 180 or 360.
    RotationTrack t{"transform.rotation", {}};
    for (int i = 0; i <= 12; ++i) t.keys.push_back(rkey(i, yaw(90.0 * i), Interpolation::Cubic));
    glm::dquat prev = *evaluate(t, 0.0);
    double travelled = 0.0;
    for (int i = 1; i <= 1200; ++i) {
      const glm::dquat q = *evaluate(t, i / 100.0);
      const double step = glm::degrees(rotationAngleBetween(prev, q));
      QVERIFY2(step < 2.0, qPrintable(QString("jump of %1 degrees at t=%2").arg(step).arg(i / 100.0)));
      travelled += step;
      prev = q;
    }
    QVERIFY(std::abs(travelled - 1080.0) < 1.0);
  }

  void singleAxisCubicMatchesScalarCubic() {
    // About one axis the rotation curve is the scalar cubic of the angle.
    ScalarTrack angle{"yaw", {key(0, 0), key(1, 40), key(2.5, 45), key(3, 120)}};
    RotationTrack rot{"transform.rotation", {}};
    for (const auto& k : angle.keys) rot.keys.push_back(rkey(k.time, yaw(k.value), Interpolation::Cubic));
    for (int i = 0; i <= 300; ++i) {
      const double t = i / 100.0;
      QVERIFY(std::abs(yawOf(*evaluate(rot, t)) - *evaluate(angle, t)) < 1e-9);
    }
  }

  void rotationsExactAtKeys() {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> n(0.0, 1.0);
    RotationTrack t{"transform.rotation", {}};
    for (int i = 0; i < 20; ++i) {
      const glm::dquat q = glm::normalize(glm::dquat(n(rng), n(rng), n(rng), n(rng)));
      t.keys.push_back(rkey(i * 0.7, q, Interpolation(rng() % 3)));
    }
    for (const auto& k : t.keys) {
      const glm::dquat q = *evaluate(t, k.time);
      QVERIFY(q == k.value || q == -k.value);
    }
  }

  void sequenceJsonRoundTrip() {
    Sequence s;
    s.rate = {60000, 1001};
    s.startFrame = 10;
    s.endFrame = 35999;
    Binding cam;
    cam.entity = 3;
    cam.label = "Drone \"camera\"";
    ScalarTrack fov{"camera.fov_deg", {key(0, 50), key(10, 35, Interpolation::Linear, Ease::InOut)}};
    fov.keys[1].tangentMode = TangentMode::Broken;
    fov.keys[1].inSlope = -0.1;
    fov.keys[1].outSlope = 0.3;
    fov.keys[0].setSlope(1.0 / 3.0);
    cam.tracks.push_back(fov);
    VectorTrack pos{"transform.translation", {}};
    VectorKey vk;
    vk.time = 1e6 + 1.0 / 60.0;
    vk.value = {512345.123456789, 4412345.987654321, -0.1};
    pos.keys.push_back(vk);
    cam.tracks.push_back(pos);
    cam.tracks.push_back(RotationTrack{"transform.rotation", {rkey(0, yaw(10)), rkey(2, yaw(200), Interpolation::Cubic)}});
    cam.tracks.push_back(StepTrack{"entity.visible", {{0.0, true}, {5.5, false}}});
    PathFollow path;
    path.path.points = {{0, 0, 10}, {100, 0, 12}, {200, 50, 15}};
    path.progress.keys = {key(0, 0, Interpolation::Linear), key(60, 1)};
    path.aim = PathAim::Entity;
    path.targetEntity = 7;
    path.bank = true;
    path.maxBankDeg = 20;
    cam.path = path;
    s.bindings.push_back(cam);
    const std::string text = sequenceToJsonText(s);
    std::string error;
    const auto back = sequenceFromJsonText(text, error);
    QVERIFY2(back, error.c_str());
    QVERIFY(*back == s);
    QCOMPARE(sequenceToJsonText(*back), text);  // stable text
  }

  // The sequence's JSON text cut at every length: refused with a message,
  // or (only whitespace lost) the same sequence.
  void sequenceJsonCutAtEveryLength() {
    Sequence s;
    Binding cam;
    cam.entity = 3;
    ScalarTrack fov{"camera.fov_deg", {key(0, 40), key(2.5, 55, Interpolation::Linear)}};
    cam.tracks.push_back(fov);
    cam.tracks.push_back(RotationTrack{"transform.rotation", {rkey(0, yaw(10)), rkey(2, yaw(200), Interpolation::Cubic)}});
    cam.tracks.push_back(StepTrack{"entity.visible", {{0.0, true}, {5.5, false}}});
    s.bindings.push_back(cam);
    const std::string text = sequenceToJsonText(s);
    std::string error;
    QVERIFY2(sequenceFromJsonText(text, error), error.c_str());
    for (size_t n = 0; n < text.size(); ++n) {
      error.clear();
      const auto back = sequenceFromJsonText(std::string_view(text).substr(0, n), error);
      if (back) {
        QVERIFY2(*back == s && text.find_first_not_of(" \t\r\n", n) == std::string::npos,
                 qPrintable(QString("cut at %1 read as another sequence").arg(n)));
        continue;
      }
      QVERIFY2(!error.empty(), qPrintable(QString("cut at %1: no message").arg(n)));
    }
  }

  void sequenceJsonErrorsNameThePlace() {
    std::string error;
    QVERIFY(!sequenceFromJsonText(R"({"format":"hybridscape-sequence","version":1,"rate":[60,1],"start":0,"end":9,
      "bindings":[{"entity":1,"tracks":[{"type":"scalar","property":"x","keys":[{"t":0,"v":1,"interp":"cubc"}]}]}]})",
                                  error));
    QVERIFY2(error.find("bindings[0].tracks[0].keys[0].interp") != std::string::npos, error.c_str());
    QVERIFY(error.find("cubc") != std::string::npos);
    QVERIFY(!sequenceFromJsonText(R"({"format":"hybridscape-sequence","version":7,"rate":[60,1],"start":0,"end":9,"bindings":[]})", error));
    QVERIFY2(error.find("newer") != std::string::npos, error.c_str());
    QVERIFY(!sequenceFromJsonText("{\"format\": \"hybridscape-sequence\",\n \"version\": 1,,}", error));
    QVERIFY2(error.find("line 2, column 15") != std::string::npos, error.c_str());
  }

  // The reader is hs::parseJson plus JsonReader: a bad value names its path
  // and where it is in the text; what the old hand-written reader let
  // through (duplicate keys, `1.`) is refused; numbers too large for the
  // field are refused, not wrapped.
  void sequenceJsonIsReadStrictly() {
    const std::string head = "{\"format\": \"hybridscape-sequence\", \"version\": 1, \"rate\": [60, 1],\n";
    std::string error;
    QVERIFY(!sequenceFromJsonText(head + " \"start\": 0, \"end\": 9,\n \"bindings\": [{\"entity\": 1, \"tracks\": [\n"
                                         "  {\"type\": \"scalar\", \"property\": \"x\", \"keys\": [{\"t\": \"soon\", \"v\": 1}]}]}]}",
                                  error));
    QCOMPARE(error, std::string("bindings[0].tracks[0].keys[0].t (line 4, column 54): expected a number, not a string"));
    QVERIFY(!sequenceFromJsonText(head + " \"start\": 0, \"end\": 9, \"end\": 10, \"bindings\": []}", error));
    QVERIFY2(error.find("line 2, column 24: duplicate key \"end\"") == 0, error.c_str());
    QVERIFY(!sequenceFromJsonText(head + " \"start\": 1., \"end\": 9, \"bindings\": []}", error));
    QVERIFY2(error.find("line 2, column 13") == 0, error.c_str());
    QVERIFY(!sequenceFromJsonText(head + " \"start\": 99999999999999999999, \"end\": 9, \"bindings\": []}", error));
    QVERIFY2(error.find("start (line 2, column 11): expected a whole number") == 0, error.c_str());
    QVERIFY(!sequenceFromJsonText(head + " \"start\": 0, \"end\": 9, \"bindings\": [{\"entity\": -1, \"tracks\": []}]}", error));
    QVERIFY2(error.find("bindings[0].entity (line 2, column 48): expected a whole number from 0") == 0, error.c_str());
    QVERIFY(!sequenceFromJsonText("[]", error));
    QCOMPARE(error, std::string("line 1, column 1: expected an object, not an array"));
    // A version too large for any integer type is still "newer", with its number.
    QVERIFY(!sequenceFromJsonText(R"({"format": "hybridscape-sequence", "version": 999999999999999999999})", error));
    QVERIFY2(error.find("version (line 1, column 47): format version 1e+21 is newer") == 0, error.c_str());
    // Written members at their defaults may be left out by hand-written files.
    const auto minimal = sequenceFromJsonText(head + R"( "start": 0, "end": 9, "bindings": [{"entity": 2, "tracks": []}]})", error);
    QVERIFY2(minimal, error.c_str());
    QCOMPARE(minimal->bindings.at(0).entity, uint64_t(2));
    QCOMPARE(minimal->bindings.at(0).label, std::string());
  }

  void frameRanges() {
    std::string error;
    auto all = FrameList::parse("0-35999", error);
    QVERIFY(all);
    QCOMPARE(all->count(), int64_t(36000));
    QCOMPARE(all->toString(), std::string("0-35999"));
    auto mixed = FrameList::parse("10, 20-30", error);
    QCOMPARE(mixed->count(), int64_t(12));
    QCOMPARE(mixed->toString(), std::string("10,20-30"));
    QVERIFY(mixed->contains(25) && !mixed->contains(15));
    auto stepped = FrameList::parse("0-100x10", error);
    QCOMPARE(stepped->count(), int64_t(11));
    QCOMPARE(stepped->toString(), std::string("0-100x10"));
    auto merged = FrameList::parse("5-9,0-6,3", error);
    QCOMPARE(merged->toString(), std::string("0-9"));
    auto negative = FrameList::parse("-5--3", error);
    QCOMPARE(negative->frames(), (std::vector<int64_t>{-5, -4, -3}));
    QVERIFY(!FrameList::parse("10,,20", error));
    QVERIFY2(error.find("character 4") != std::string::npos, error.c_str());
    QVERIFY(!FrameList::parse("30-20", error));
    QVERIFY(error.find("backwards") != std::string::npos);
    QVERIFY(!FrameList::parse("abc", error));
    QVERIFY(!FrameList::parse("", error));
    QVERIFY(!FrameList::parse("1-5y2", error));
    const auto chunks = all->chunks(600);
    QCOMPARE(chunks.size(), size_t(60));
    QCOMPARE(chunks.front().toString(), std::string("0-599"));
    QCOMPARE(chunks.back().toString(), std::string("35400-35999"));
    const auto small = mixed->chunks(5);
    QCOMPARE(small.size(), size_t(3));
    QCOMPARE(small[0].toString(), std::string("10,20-23"));
    QCOMPARE(small[2].toString(), std::string("29-30"));
    // Rates.
    QCOMPARE(parseFrameRate("59.94", error)->num, int64_t(60000));
    QCOMPARE(parseFrameRate("60000/1001", error)->den, int64_t(1001));
    QCOMPARE(parseFrameRate("60", error)->fps(), 60.0);
    QVERIFY(!parseFrameRate("fast", error));
  }

  // What an operation accepts of a frame list: frames 0 .. 2^31-1 (the
  // list itself may hold negative frames).
  void frameBoundsOfOperations() {
    std::string error;
    const auto bounds = FrameList::parse("0,2147483647", error), negative = FrameList::parse("-5-2", error),
               beyond = FrameList::parse("10,2147483648", error);
    QVERIFY(bounds && negative && beyond);
    QVERIFY(checkFrameBounds(*bounds, "--frames", error));
    QVERIFY(!checkFrameBounds(*negative, "--frames", error));
    QCOMPARE(error, std::string("--frames: frame -5 is out of range (0 to 2147483647)"));
    QVERIFY(!checkFrameBounds(*beyond, "Frames", error));
    QCOMPARE(error, std::string("Frames: frame 2147483648 is out of range (0 to 2147483647)"));
    QVERIFY(checkFrameBounds(FrameList(), "--frames", error));
  }

  void outputPatterns() {
    std::string error;
    auto p = OutputPattern::parse("frames/f_%05d.png", error);
    QCOMPARE(p->path(42), std::string("frames/f_00042.png"));
    QCOMPARE(p->path(42, Eye::Left), std::string("frames/f_00042_left.png"));
    QCOMPARE(OutputPattern::parse("f_####.exr", error)->path(7), std::string("f_0007.exr"));
    QCOMPARE(OutputPattern::parse("%V/f_%04d.png", error)->path(7, Eye::Right), std::string("right/f_0007.png"));
    QCOMPARE(OutputPattern::parse("f_%d_%v.tif", error)->path(7, Eye::Left), std::string("f_7_l.tif"));
    QCOMPARE(OutputPattern::parse("100%%_%03d.jpg", error)->path(1), std::string("100%_001.jpg"));
    QVERIFY(!OutputPattern::parse("frames/f.png", error));
    QVERIFY(error.find("no frame number") != std::string::npos);
    QVERIFY(!OutputPattern::parse("f_%05d_%05d.png", error));
    QVERIFY(!OutputPattern::parse("f_%s.png", error));
  }
};

QTEST_APPLESS_MAIN(TestTracks)
#include "test_sequencer_tracks.moc"

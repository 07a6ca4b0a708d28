#include "sequencer/track.h"

#include <algorithm>
#include <cmath>

#include "sequencer/interpolation.h"

namespace hs::sequencer {

namespace {

// Index of the last key with time <= t; -1 before the first key.
template <class K>
std::ptrdiff_t keyAtOrBefore(const std::vector<K>& keys, double t) {
  const auto it = std::upper_bound(keys.begin(), keys.end(), t,
                                   [](double time, const K& k) { return time < k.time; });
  return std::distance(keys.begin(), it) - 1;
}

double component(double v, int) { return v; }
double component(const glm::dvec3& v, int i) { return v[i]; }
void setComponent(double& v, int, double x) { v = x; }
void setComponent(glm::dvec3& v, int i, double x) { v[i] = x; }
template <class V> constexpr int componentCount() { return std::is_same_v<V, double> ? 1 : 3; }

// Clamped automatic slope of key j, component c (see clampedSlope()).
template <class V>
double autoSlope(const std::vector<Key<V>>& keys, size_t j, int c) {
  const bool hasPrev = j > 0 && keys[j - 1].time < keys[j].time;
  const bool hasNext = j + 1 < keys.size() && keys[j + 1].time > keys[j].time;
  // Ends of the track (or of a piece cut by a jump) are flat: the curve
  // joins the held value smoothly, as Blender's Auto Clamped does.
  if (!hasPrev || !hasNext) return 0.0;
  const double hPrev = keys[j].time - keys[j - 1].time;
  const double hNext = keys[j + 1].time - keys[j].time;
  const double dPrev = (component(keys[j].value, c) - component(keys[j - 1].value, c)) / hPrev;
  const double dNext = (component(keys[j + 1].value, c) - component(keys[j].value, c)) / hNext;
  return clampedSlope(dPrev, dNext, hPrev, hNext);
}

template <class V>
double leavingSlope(const std::vector<Key<V>>& keys, size_t j, int c) {
  return keys[j].tangentMode == TangentMode::Auto ? autoSlope(keys, j, c) : component(keys[j].outSlope, c);
}
template <class V>
double arrivingSlope(const std::vector<Key<V>>& keys, size_t j, int c) {
  switch (keys[j].tangentMode) {
    case TangentMode::Auto: return autoSlope(keys, j, c);
    case TangentMode::User: return component(keys[j].outSlope, c);
    case TangentMode::Broken: return component(keys[j].inSlope, c);
  }
  return 0.0;
}

// Value and slope of a scalar or vector track at t.
template <class V>
std::optional<std::pair<V, V>> evaluateCurve(const std::vector<Key<V>>& keys, double t) {
  if (keys.empty()) return std::nullopt;
  const V zero(0.0);
  const std::ptrdiff_t k = keyAtOrBefore(keys, t);
  if (k < 0) return std::pair{keys.front().value, zero};
  if (size_t(k) + 1 >= keys.size()) return std::pair{keys.back().value, zero};
  const Key<V>& a = keys[size_t(k)];
  const Key<V>& b = keys[size_t(k) + 1];
  if (a.interpolation == Interpolation::Constant) return std::pair{a.value, zero};
  // At t == a.time, u is 0 and both forms below return a.value bit for bit
  // (the other Hermite weights are exactly 0), with the slope leaving a.
  const double h = b.time - a.time;  // > 0: b is after the last key at or before t
  const double u = (t - a.time) / h;
  const double s = easeValue(a.ease, u);
  const double ds = easeSlope(a.ease, u) / h;  // ds/dt
  V value = a.value, slope = zero;
  for (int c = 0; c < componentCount<V>(); ++c) {
    const double p0 = component(a.value, c), p1 = component(b.value, c);
    double v, dv;
    if (a.interpolation == Interpolation::Linear) {
      v = p0 + (p1 - p0) * s;
      dv = (p1 - p0) * ds;
    } else {
      const double m0 = leavingSlope(keys, size_t(k), c) * h;
      const double m1 = arrivingSlope(keys, size_t(k) + 1, c) * h;
      v = hermite(p0, m0, p1, m1, s);
      dv = hermiteSlope(p0, m0, p1, m1, s) * ds;
    }
    setComponent(value, c, v);
    setComponent(slope, c, dv);
  }
  return std::pair{value, slope};
}

// Angular velocity (body frame, rad/s) of rotation key j: automatic from the
// segment rotations on its two sides, component by component in the key's
// frame (the axis of a rotation is the same in its start and end frames, so
// both sides are expressed in key j's frame).
glm::dvec3 autoAngularVelocity(const std::vector<RotationKey>& keys, size_t j) {
  const bool hasPrev = j > 0 && keys[j - 1].time < keys[j].time;
  const bool hasNext = j + 1 < keys.size() && keys[j + 1].time > keys[j].time;
  if (!hasPrev || !hasNext) return glm::dvec3(0.0);
  const double hPrev = keys[j].time - keys[j - 1].time;
  const double hNext = keys[j + 1].time - keys[j].time;
  const glm::dvec3 dPrev = segmentRotation(keys[j - 1].value, keys[j].value) / hPrev;
  const glm::dvec3 dNext = segmentRotation(keys[j].value, keys[j + 1].value) / hNext;
  glm::dvec3 w;
  for (int c = 0; c < 3; ++c) w[c] = clampedSlope(dPrev[c], dNext[c], hPrev, hNext);
  return w;
}

glm::dvec3 leavingAngular(const std::vector<RotationKey>& keys, size_t j) {
  return keys[j].tangentMode == TangentMode::Auto ? autoAngularVelocity(keys, j) : keys[j].outSlope;
}
glm::dvec3 arrivingAngular(const std::vector<RotationKey>& keys, size_t j) {
  switch (keys[j].tangentMode) {
    case TangentMode::Auto: return autoAngularVelocity(keys, j);
    case TangentMode::User: return keys[j].outSlope;
    case TangentMode::Broken: return keys[j].inSlope;
  }
  return glm::dvec3(0.0);
}

}  // namespace

namespace {

// The blossom of a cubic Bezier (de Casteljau with a parameter per level):
// f(s, s, s) is the curve at s; f(s0..., s1...) the control points of its
// piece on [s0, s1].
double blossom(const double b[4], double u1, double u2, double u3) {
  double p[3], q[2];
  for (int i = 0; i < 3; ++i) p[i] = (1.0 - u1) * b[i] + u1 * b[i + 1];
  for (int i = 0; i < 2; ++i) q[i] = (1.0 - u2) * p[i] + u2 * p[i + 1];
  return (1.0 - u3) * q[0] + u3 * q[1];
}

template <class V>
void widen(std::pair<V, V>& r, const V& v) {
  for (int c = 0; c < componentCount<V>(); ++c) {
    double lo = component(r.first, c), hi = component(r.second, c);
    setComponent(r.first, c, std::min(lo, component(v, c)));
    setComponent(r.second, c, std::max(hi, component(v, c)));
  }
}

template <class V>
std::optional<std::pair<V, V>> curveRange(const std::vector<Key<V>>& keys, double t0, double t1) {
  const auto at0 = evaluateCurve(keys, t0);
  if (!at0) return std::nullopt;
  if (t1 < t0) std::swap(t0, t1);
  std::pair<V, V> r{at0->first, at0->first};
  widen(r, evaluateCurve(keys, t1)->first);
  for (size_t k = 0; k < keys.size(); ++k) {
    // A key inside the interval is a value the track takes (a jump's every side).
    if (keys[k].time >= t0 && keys[k].time <= t1) widen(r, keys[k].value);
    if (k + 1 >= keys.size()) continue;
    const Key<V>& a = keys[k];
    const Key<V>& b = keys[k + 1];
    // Segments that overlap (t0, t1); a jump (b.time == a.time) has no inside.
    if (!(a.time < b.time) || !(a.time < t1) || !(b.time > t0)) continue;
    if (a.interpolation == Interpolation::Constant) {
      widen(r, a.value);
      continue;
    }
    // The part of the segment inside the window, in the eased parameter
    // s = e(u): e is monotone, so u in [ua, ub] is s in [e(ua), e(ub)].
    const double h = b.time - a.time;
    const double s0 = easeValue(a.ease, std::clamp((t0 - a.time) / h, 0.0, 1.0));
    const double s1 = easeValue(a.ease, std::clamp((t1 - a.time) / h, 0.0, 1.0));
    V lo = a.value, hi = a.value;
    for (int c = 0; c < componentCount<V>(); ++c) {
      const double p0 = component(a.value, c), p1 = component(b.value, c);
      double x0, x1;
      if (a.interpolation == Interpolation::Linear) {
        x0 = p0 + (p1 - p0) * s0;
        x1 = p0 + (p1 - p0) * s1;
      } else {
        // The cubic's Bezier polygon on [s0, s1] (its blossom): the piece
        // lies inside it, and it shrinks to the piece as the window does.
        const double m0 = leavingSlope(keys, k, c) * h, m1 = arrivingSlope(keys, k + 1, c) * h;
        const double bz[4] = {p0, p0 + m0 / 3.0, p1 - m1 / 3.0, p1};
        const double c0 = blossom(bz, s0, s0, s0), c1 = blossom(bz, s0, s0, s1);
        const double c2 = blossom(bz, s0, s1, s1), c3 = blossom(bz, s1, s1, s1);
        x0 = std::min({c0, c1, c2, c3});
        x1 = std::max({c0, c1, c2, c3});
      }
      setComponent(lo, c, std::min(x0, x1));
      setComponent(hi, c, std::max(x0, x1));
    }
    widen(r, lo);
    widen(r, hi);
  }
  return r;
}

bool sameOrientation(const glm::dquat& a, const glm::dquat& b) { return a == b || a == -b; }

}  // namespace

std::optional<std::pair<double, double>> valueRange(const ScalarTrack& track, double t0, double t1) {
  return curveRange(track.keys, t0, t1);
}

std::optional<std::pair<glm::dvec3, glm::dvec3>> valueRange(const VectorTrack& track, double t0, double t1) {
  return curveRange(track.keys, t0, t1);
}

bool turnsDuring(const RotationTrack& track, double t0, double t1) {
  const auto& keys = track.keys;
  if (keys.empty()) return false;
  if (t1 < t0) std::swap(t0, t1);
  const glm::dquat first = *evaluate(track, t0);
  for (size_t k = 0; k < keys.size(); ++k) {
    if (keys[k].time >= t0 && keys[k].time <= t1 && !sameOrientation(keys[k].value, first)) return true;
    if (k + 1 >= keys.size()) continue;
    const RotationKey& a = keys[k];
    const RotationKey& b = keys[k + 1];
    if (!(a.time < b.time) || !(a.time < t1) || !(b.time > t0)) continue;
    if (!sameOrientation(a.value, first)) return true;
    if (a.interpolation == Interpolation::Constant) continue;
    if (!sameOrientation(b.value, first)) return true;
    if (a.interpolation == Interpolation::Cubic &&
        (leavingAngular(keys, k) != glm::dvec3(0.0) || arrivingAngular(keys, k + 1) != glm::dvec3(0.0)))
      return true;
  }
  return false;
}

const std::string& trackProperty(const Track& t) {
  return std::visit([](const auto& x) -> const std::string& { return x.property; }, t);
}

size_t trackKeyCount(const Track& t) {
  return std::visit([](const auto& x) { return x.keys.size(); }, t);
}

std::optional<double> evaluate(const ScalarTrack& track, double t) {
  const auto r = evaluateCurve(track.keys, t);
  if (!r) return std::nullopt;
  return r->first;
}

std::optional<ScalarSample> evaluateWithSlope(const ScalarTrack& track, double t) {
  const auto r = evaluateCurve(track.keys, t);
  if (!r) return std::nullopt;
  return ScalarSample{r->first, r->second};
}

std::optional<glm::dvec3> evaluate(const VectorTrack& track, double t) {
  const auto r = evaluateCurve(track.keys, t);
  if (!r) return std::nullopt;
  return r->first;
}

std::optional<glm::dquat> evaluate(const RotationTrack& track, double t) {
  const auto& keys = track.keys;
  if (keys.empty()) return std::nullopt;
  const std::ptrdiff_t k = keyAtOrBefore(keys, t);
  if (k < 0) return keys.front().value;
  if (size_t(k) + 1 >= keys.size()) return keys.back().value;
  const RotationKey& a = keys[size_t(k)];
  const RotationKey& b = keys[size_t(k) + 1];
  if (t == a.time || a.interpolation == Interpolation::Constant) return a.value;
  const double h = b.time - a.time;
  const double s = easeValue(a.ease, (t - a.time) / h);
  const glm::dvec3 r = segmentRotation(a.value, b.value);
  if (a.interpolation == Interpolation::Linear) return slerpAlong(a.value, r, s);
  // Cubic: a Bezier curve on the rotation group evaluated by de Casteljau's
  // construction with slerps (Shoemake). Its control points sit one third
  // of the segment's angular velocity * h from the ends, so the angular
  // velocity at each end is exactly the key's; rotations about one fixed
  // axis reduce it to the scalar cubic of the angle.
  const glm::dquat b0 = a.value;
  const glm::dquat b3 = a.value * rotationFromVector(r);
  const glm::dquat b1 = b0 * rotationFromVector(leavingAngular(keys, size_t(k)) * (h / 3.0));
  const glm::dquat b2 = b3 * rotationFromVector(arrivingAngular(keys, size_t(k) + 1) * (-h / 3.0));
  const glm::dquat p01 = slerpShortest(b0, b1, s), p12 = slerpShortest(b1, b2, s), p23 = slerpShortest(b2, b3, s);
  const glm::dquat p012 = slerpShortest(p01, p12, s), p123 = slerpShortest(p12, p23, s);
  return slerpShortest(p012, p123, s);
}

std::optional<bool> evaluate(const StepTrack& track, double t) {
  if (track.keys.empty()) return std::nullopt;
  const std::ptrdiff_t k = keyAtOrBefore(track.keys, t);
  return track.keys[size_t(std::max<std::ptrdiff_t>(k, 0))].value;
}

void sortKeys(Track& track) {
  std::visit(
      [](auto& tr) {
        std::stable_sort(tr.keys.begin(), tr.keys.end(), [](const auto& x, const auto& y) { return x.time < y.time; });
      },
      track);
}

namespace {
bool finite(double v) { return std::isfinite(v); }
bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::dquat& q) { return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z); }
bool finite(bool) { return true; }
}  // namespace

std::vector<std::string> trackProblems(const Track& track) {
  std::vector<std::string> out;
  std::visit(
      [&](const auto& tr) {
        const std::string where = "track '" + tr.property + "'";
        if (tr.property.empty()) out.push_back("a track has no property path");
        for (size_t i = 0; i < tr.keys.size(); ++i) {
          const auto& k = tr.keys[i];
          const std::string key = where + " key " + std::to_string(i);
          if (!std::isfinite(k.time)) out.push_back(key + ": time is not a finite number");
          if (!finite(k.value)) out.push_back(key + ": value is not a finite number");
          if (i > 0 && k.time < tr.keys[i - 1].time) out.push_back(key + ": keys are not in time order");
          if constexpr (std::is_same_v<std::decay_t<decltype(k)>, RotationKey>) {
            if (finite(k.value) && std::abs(glm::length(k.value) - 1.0) > 1e-6)
              out.push_back(key + ": rotation is not a unit quaternion (normalize it)");
          }
          if constexpr (!std::is_same_v<std::decay_t<decltype(k)>, StepKey>) {
            if (!finite(k.inSlope) || !finite(k.outSlope)) out.push_back(key + ": slope is not a finite number");
          }
        }
      },
      track);
  return out;
}

}  // namespace hs::sequencer

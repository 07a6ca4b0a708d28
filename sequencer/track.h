#pragma once
// Tracks: the keys of one animated property of one entity, and their pure
// evaluation at a time t. A track is plain data (what the .hscene file and
// undo store); evaluating it reads only the keys and t.
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "sequencer/keys.h"

namespace hs::sequencer {

// `property` is a path into scene/fields.h's table ("camera.fov_deg",
// "transform.translation", "entity.visible"; "material.roughness" and
// "settings.fog_density" on material and settings bindings), except rotation tracks,
// which target "transform.rotation": the quaternion itself, never the
// Euler-angle field, so interpolation keeps the shortest path.
struct ScalarTrack {
  std::string property;
  std::vector<ScalarKey> keys;  // sorted by time (sortKeys)
  bool operator==(const ScalarTrack&) const = default;
};
struct VectorTrack {
  std::string property;
  std::vector<VectorKey> keys;  // each component is a curve of its own, like Blender's x/y/z F-curves
  bool operator==(const VectorTrack&) const = default;
};
struct RotationTrack {
  std::string property = "transform.rotation";
  std::vector<RotationKey> keys;  // unit quaternions, camera/entity to parent
  bool operator==(const RotationTrack&) const = default;
};
struct StepTrack {
  std::string property;
  std::vector<StepKey> keys;
  bool operator==(const StepTrack&) const = default;
};

using Track = std::variant<ScalarTrack, VectorTrack, RotationTrack, StepTrack>;

const std::string& trackProperty(const Track& t);
size_t trackKeyCount(const Track& t);

// Rules shared by every track type:
// - Before the first key and after the last the value holds (no extrapolation).
// - Keys at the same time (coincident) make a jump: at exactly that time the
//   last of them holds (the curve is right-continuous), just before it the
//   first one is approached; keys between them are never seen. The jump
//   splits the track into independent pieces whose auto slopes treat the
//   jump like the end of the track (flat).
// - At a key's time the key's value comes back bit for bit (rotations up
//   to the quaternion's sign, which is immaterial).
// - Time is double seconds and segments use the relative parameter
//   u = (t - t0) / (t1 - t0), so keys at t = 1e6 s (ulp 1.2e-10 s) keep
//   full precision for frame spacings of 1/60 s.
// A track with no keys has no value (nullopt): the property is not animated.
std::optional<double> evaluate(const ScalarTrack& track, double t);
std::optional<glm::dvec3> evaluate(const VectorTrack& track, double t);
std::optional<glm::dquat> evaluate(const RotationTrack& track, double t);
std::optional<bool> evaluate(const StepTrack& track, double t);

// An enclosure of every value a scalar track (or each component of a
// vector track) takes for t in [t0, t1]: the lowest and highest value, or
// a little wider. Proven, not sampled: the piece of a cubic segment inside
// the interval lies inside its own Bezier control polygon (the blossom of
// p0, p0 + m0/3, p1 - m1/3, p1 on the piece's eased parameters; an ease is
// monotone, so it only re-times the piece), which closes in on the piece
// as the interval shrinks; linear and constant pieces give their exact
// range. What a bound over a time window needs (particles/bounds.h).
// nullopt: no keys.
std::optional<std::pair<double, double>> valueRange(const ScalarTrack& track, double t0, double t1);
std::optional<std::pair<glm::dvec3, glm::dvec3>> valueRange(const VectorTrack& track, double t0, double t1);
// Whether a rotation track may give two different orientations at times
// in [t0, t1] (false: evaluate() is one orientation there). Conservative:
// any segment that overlaps the interval with different end keys or a
// non-zero end velocity turns.
bool turnsDuring(const RotationTrack& track, double t0, double t1);

// Value and time derivative (units per second) of a scalar track; a camera
// path uses the derivative of its progress for the speed that banking needs.
struct ScalarSample {
  double value = 0.0;
  double slope = 0.0;
};
std::optional<ScalarSample> evaluateWithSlope(const ScalarTrack& track, double t);

// Stable sort by time: keys entered at the same time keep their order, so
// a deliberate jump stays the way round it was made.
void sortKeys(Track& track);

// Problems that make a track unusable or surprising, each naming the key:
// unsorted keys, non-finite times or values, zero-length rotation keys.
std::vector<std::string> trackProblems(const Track& track);

}  // namespace hs::sequencer

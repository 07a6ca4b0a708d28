#pragma once
// Keys of animation tracks: plain, serializable data. How a key shapes the
// curve is defined in interpolation.h and docs/sequencer.md.
#include <cstdint>
#include <optional>
#include <string_view>
#include <type_traits>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace hs::sequencer {

// How the segment that *leaves* a key is drawn (as in Blender and Unreal:
// a key owns the segment to its right).
enum class Interpolation : uint8_t { Constant, Linear, Cubic };

// Where a cubic segment's slopes at a key come from.
//   Auto:   computed from the neighbouring keys, clamped so the curve never
//           overshoots (monotone between keys, flat at extremes and at the
//           ends of the track), like Blender's "Auto Clamped".
//   User:   one slope on both sides (outSlope; inSlope is ignored and kept
//           equal by setSlope()), like Unreal's "User".
//   Broken: inSlope arrives, outSlope leaves; they differ (Unreal's "Break").
enum class TangentMode : uint8_t { Auto, User, Broken };

// A time remap of the segment that leaves a key: the segment's normalized
// time u in [0,1] becomes e(u) before interpolating. e is the cubic Hermite
// with e(0)=0, e(1)=1 and end slopes (e'(0), e'(1)):
//   None  (1,1)  e(u) = u
//   In    (0,1)  e(u) = 2u^2 - u^3          slow start, joins linear speed
//   Out   (1,0)  e(u) = 1 - 2(1-u)^2 + (1-u)^3   slow end
//   InOut (0,0)  e(u) = 3u^2 - 2u^3          slow start and end (smoothstep)
// e is monotone on [0,1], so an eased segment never leaves the range it
// spans without the ease.
enum class Ease : uint8_t { None, In, Out, InOut };

template <class Value>
constexpr Value defaultKeyValue() {
  if constexpr (std::is_same_v<Value, glm::dquat>) return glm::dquat(1.0, 0.0, 0.0, 0.0);
  else return Value(0.0);
}

// Slopes are value units per second. For rotation keys they are the angular
// velocity in the key's own (body) frame, radians per second.
template <class Value, class Slope = Value>
struct Key {
  double time = 0.0;  // seconds on the sequence's clock
  Value value = defaultKeyValue<Value>();
  Interpolation interpolation = Interpolation::Cubic;
  TangentMode tangentMode = TangentMode::Auto;
  Slope inSlope = Slope(0.0);
  Slope outSlope = Slope(0.0);
  Ease ease = Ease::None;

  // User tangents: one slope, both sides (see TangentMode).
  void setSlope(const Slope& s) {
    tangentMode = TangentMode::User;
    inSlope = outSlope = s;
  }
  bool operator==(const Key&) const = default;
};

using ScalarKey = Key<double>;
using VectorKey = Key<glm::dvec3>;
using RotationKey = Key<glm::dquat, glm::dvec3>;

// Boolean and other on/off properties (visibility) only step: the value of
// the last key at or before t holds until the next key.
struct StepKey {
  double time = 0.0;
  bool value = true;
  bool operator==(const StepKey&) const = default;
};

const char* interpolationName(Interpolation i);
const char* tangentModeName(TangentMode m);
const char* easeName(Ease e);
std::optional<Interpolation> interpolationFromName(std::string_view s);
std::optional<TangentMode> tangentModeFromName(std::string_view s);
std::optional<Ease> easeFromName(std::string_view s);

}  // namespace hs::sequencer

#pragma once
// The curve maths behind tracks: eases, cubic Hermite segments, clamped
// automatic slopes and the quaternion rules (shortest path, the 180° tie).
// Free functions of their arguments only, so a track evaluates the same at
// any time in any order (DESIGN.md, "Time and determinism").
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "sequencer/keys.h"

namespace hs::sequencer {

// e(u) and e'(u) of keys.h's Ease, for u in [0,1].
double easeValue(Ease ease, double u);
double easeSlope(Ease ease, double u);

// Cubic Hermite on the unit interval: p0 -> p1 with end derivatives d0, d1
// (already multiplied by the segment length, i.e. per unit u). At u = 0 it
// returns p0 bit for bit (the other basis weights are exactly 0).
double hermite(double p0, double d0, double p1, double d1, double u);
double hermiteSlope(double p0, double d0, double p1, double d1, double u);  // d/du

// Clamped automatic slope at a key from the secants on its two sides
// (Fritsch-Butland weighted harmonic mean, as in PCHIP): zero where the
// secants differ in sign or one is zero (the key is an extreme or sits on
// a plateau); otherwise a slope with |m| <= 3 min(|dPrev|, |dNext|), which
// is inside Fritsch and Carlson's monotonicity region, so a segment whose
// two slopes come from here never leaves the range of its end keys.
// hPrev, hNext: the lengths (seconds) of the two segments.
double clampedSlope(double dPrev, double dNext, double hPrev, double hNext);

// --- Rotations ---------------------------------------------------------
// Rotation vectors: axis * angle (radians), the logarithm of a rotation.
glm::dvec3 rotationVector(const glm::dquat& q);  // of a unit quaternion, angle in [0, pi]
glm::dquat rotationFromVector(const glm::dvec3& v);

// Quaternions whose dot product is within this of zero are treated as
// exactly 180° apart (the angles differ from 180° by less than 2e-9 rad).
// Keys typed as Euler angles (yaw 0 -> 180) land within rounding of zero,
// on either side; without the band their direction would be decided by
// rounding noise.
constexpr double kHalfTurnTolerance = 1e-9;

// The rotation of a segment from an earlier key to a later one, as a
// rotation vector in the earlier key's body frame, always the shortest way
// (angle <= 180°). At exactly 180° (|dot| <= kHalfTurnTolerance) both ways
// are equally short; the segment then turns positively (right hand) about
// the world axis of the rotation chosen with positive Z, else positive Y,
// else positive X: a 180° yaw turns counter-clockwise seen from above.
// The rule depends on the ordered pair only, never on the quaternions'
// signs, so every evaluation of the segment takes the same way.
glm::dvec3 segmentRotation(const glm::dquat& earlier, const glm::dquat& later);

// Spherical linear interpolation along a body rotation vector:
// from * exp(u * v).
glm::dquat slerpAlong(const glm::dquat& from, const glm::dvec3& bodyRotation, double u);
// Spherical interpolation between two orientations (shortest way, the rule above).
glm::dquat slerpShortest(const glm::dquat& a, const glm::dquat& b, double u);

// Angle between two orientations (radians, 0..pi), independent of sign.
double rotationAngleBetween(const glm::dquat& a, const glm::dquat& b);

}  // namespace hs::sequencer

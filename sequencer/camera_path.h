#pragma once
// A camera path: a smooth spline through points, travelled at a speed set
// by a progress track (linear keys = constant speed), aiming along the path,
// at a point or at an entity, optionally banking into turns.
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/params.h"
#include "sequencer/track.h"

namespace hs::sequencer {

struct CameraPath {
  std::vector<glm::dvec3> points;  // world space, metres; the spline passes through each
  bool operator==(const CameraPath&) const = default;
};

// The spline of a path, parameterised by arc length. Immutable: built once
// from the points (a pure function of them), then queried from any thread.
//
// The curve is a natural cubic spline (C2: continuous curvature, so the
// bank angle derived from it has no jumps at the points; a Catmull-Rom
// spline is only C1 and its curvature jumps at every point) with chord-length
// knots, in coordinates relative to the first point so UTM-sized positions
// lose nothing. Arc length is integrated with 5-point Gauss-Legendre on 16
// sub-intervals per span and inverted by safeguarded Newton iteration, which
// makes |dP/ds| = 1 to about 1e-9 (tests measure it; the budget is 0.5%).
class PathSampler {
 public:
  PathSampler() = default;
  explicit PathSampler(const std::vector<glm::dvec3>& points);

  bool empty() const { return points_.empty(); }
  double length() const { return tableArc_.empty() ? 0.0 : tableArc_.back(); }

  // s: metres along the path, clamped to [0, length()].
  glm::dvec3 position(double s) const;
  glm::dvec3 tangent(double s) const;         // unit direction of travel
  glm::dvec3 curvatureVector(double s) const;  // d2P/ds2 = kappa * normal (1/m)

  // The spline's own (chord-length) parameter, for comparing against the
  // naive parameterisation; 0..parameterLength().
  double parameterAt(double s) const;
  double parameterLength() const { return knots_.empty() ? 0.0 : knots_.back(); }
  glm::dvec3 positionAtParameter(double tau) const;
  // A box that holds the whole curve, world space: each cubic span lies in
  // the convex hull of its Bézier control points (its ends, and a third of
  // the span along the end tangents). A single point: that point.
  std::pair<glm::dvec3, glm::dvec3> box() const;

 private:
  struct Local {
    size_t span;
    double a, b, h;  // Hermite weights A = (t1 - tau)/h, B = 1 - A
  };
  Local locate(double tau) const;
  glm::dvec3 derivative(double tau) const;
  glm::dvec3 secondDerivative(double tau) const;
  double speedIntegral(double tau0, double tau1) const;

  glm::dvec3 origin_{0.0};
  std::vector<glm::dvec3> points_;   // relative to origin_, consecutive duplicates removed
  std::vector<double> knots_;        // cumulative chord length
  std::vector<glm::dvec3> second_;   // second derivatives at the knots
  std::vector<double> tableTau_;     // sub-interval ends
  std::vector<double> tableArc_;     // arc length at tableTau_
};

enum class PathAim : uint8_t {
  Tangent,  // look along the direction of travel
  Point,    // look at targetPoint
  Entity    // look at targetEntity's position (resolved by the caller)
};

struct PathFollow {
  CameraPath path;
  // Share of the path's length travelled, 0..1, over sequence time. Two
  // linear keys give constant speed; eases or cubic keys start and stop
  // softly. Values outside 0..1 hold at the ends.
  ScalarTrack progress{"path.progress", {}};
  PathAim aim = PathAim::Tangent;
  glm::dvec3 targetPoint{0.0};
  uint64_t targetEntity = 0;
  // Banking: the roll of a coordinated turn, atan(bankScale * v^2 * kappa / g),
  // limited smoothly to maxBankDeg (maxBankDeg * tanh(roll / maxBankDeg)),
  // rolling into the turn (a left turn lifts the right side of the frame).
  bool bank = false;
  double bankScale = 1.0;
  double maxBankDeg = 30.0;
  bool operator==(const PathFollow&) const = default;
};

// PathFollow's parameters as `path` and the Camera Path panel set them,
// declared once: look_at_m, bank_deg (0 turns banking off), bank_scale.
const std::vector<ParamDecl>& pathFollowParamDecls();

struct PathPose {
  glm::dvec3 position{0.0};
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // camera to world: looks down -Z, +Y up
  double speed = 0.0;    // m/s along the path
  double bankDeg = 0.0;  // roll applied, positive = into a left turn
  bool aimFallback = false;  // the target was unknown or at the camera: aimed along the path
};

// The pose at time t. `target` is the entity's position when aim is Entity
// (nullopt if it could not be resolved).
PathPose evaluatePath(const PathFollow& follow, const PathSampler& sampler, double t,
                      std::optional<glm::dvec3> target = std::nullopt);

// Orientation of a camera (-Z forward, +Y up) looking along `forward` with
// world +Z as up. Looking straight up or down, world +Y replaces +Z as the
// up hint (the one case where the result jumps; a path should not aim
// exactly vertically at a key).
glm::dquat lookRotation(const glm::dvec3& forward);

}  // namespace hs::sequencer

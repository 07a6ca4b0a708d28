#pragma once
// Stereo comfort: the nearest and farthest screen parallax of a rendered
// pair, as a share of the image width, from its depth buffers, checked
// against a budget (default -1% in front of the screen to +2% behind it).
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sequencer/stereo_rig.h"

namespace hs::sequencer {

struct ComfortBudget {
  double nearest = -0.01;   // most negative parallax allowed (in front of the screen)
  double farthest = 0.02;   // most positive parallax allowed (behind the screen)
};

enum class DepthKind : uint8_t {
  Linear,    // view depth in metres along -Z; +inf (or <= 0) where nothing was drawn
  ReversedZ  // render/'s depth buffer: 1 at near, 0 at far (0 = cleared, the sky)
};

struct DepthImage {
  int width = 0;
  int height = 0;
  const float* depth = nullptr;  // top row first
  DepthKind kind = DepthKind::Linear;
  double nearClip = 0.1;   // for ReversedZ
  double farClip = 50000;  // for ReversedZ
};

// View depth in metres from a reversed-Z value: n f / (d (f - n) + n).
double linearDepthFromReversedZ(double d, double nearClip, double farClip);

struct ComfortResult {
  bool hasPixels = false;
  double nearestParallax = 0.0;   // share of image width, negative = in front
  double farthestParallax = 0.0;
  double nearestDepth = std::numeric_limits<double>::infinity();  // metres
  double farthestDepth = 0.0;     // +inf when the sky is visible
  bool withinBudget = true;
  std::string message;            // "" when within budget
};

struct ComfortOptions {
  ComfortBudget budget;
  // Pixels with no geometry (the sky) are at infinity: they show the largest
  // positive parallax of the rig, which the eyes must diverge to if it
  // exceeds the eye separation on the screen. Off to ignore the sky.
  bool skyAtInfinity = true;
  int stride = 1;  // check every stride-th pixel in x and y (1: all)
};

// Parallax of every visible point. Off-axis and parallel rigs: parallax
// depends on depth alone, so the extremes come from the depth range
// (exact, fast). Toe-in: each pixel of the left depth image is lifted to 3D
// and projected into the right eye (and the right image into the left, when
// given), since its parallax varies across the frame.
ComfortResult checkComfort(const StereoCameras& eyes, const DepthImage& left, const DepthImage* right,
                           const ComfortOptions& options = {});

// The frames of a run that broke the budget, from per-frame results.
struct FrameComfort {
  int64_t frame = 0;
  ComfortResult result;
};
std::vector<int64_t> framesOutsideBudget(const std::vector<FrameComfort>& frames);

// An off-axis rig that maps the scene's depth range [nearDepth, farDepth]
// (farDepth may be +inf) exactly onto the budget, for a camera with the
// given horizontal half-angle tangent tan(fovX/2): interaxial
// b = 2 tan(fovX/2) (far - near) / (1/Zn - 1/Zf) and convergence
// 1/C = 2 tan(fovX/2) far / b + 1/Zf. nullopt if the range is empty.
std::optional<StereoRig> suggestRig(double nearDepth, double farDepth, double tanHalfFovX,
                                    const ComfortBudget& budget = {});

}  // namespace hs::sequencer

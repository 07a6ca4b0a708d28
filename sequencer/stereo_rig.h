#pragma once
// Stereo rig maths: from one (mono) camera and the rig settings to the two
// eye cameras the renderer draws. No GL; the eye projection has the same
// layout as render::RenderView::projection() (reversed Z, [0,1] depth, the
// off-axis shift added to NDC x), so render/stereo_views.cpp copies
// ndcShiftX into RenderView::projectionShift.x.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace hs::sequencer {

enum class StereoMode : uint8_t {
  OffAxis,   // parallel eyes, asymmetric frusta meeting at the convergence plane (default)
  Parallel,  // parallel eyes, symmetric frusta: zero parallax only at infinity
  ToeIn      // eyes rotated to cross at the convergence point: vertical parallax (keystone) off-centre
};

// Where the rig's origin (the mono camera) sits. The zero-parallax window is
// always centred between the eyes (as in Blender), so with a Left pivot the
// left eye sees what the mono camera sees, shifted by the off-axis window.
enum class RigPivot : uint8_t { Left, Centre, Right };

struct StereoRig {
  StereoMode mode = StereoMode::OffAxis;
  double interaxial = 0.065;   // metres between the two eyes
  double convergence = 10.0;   // metres from the eyes to the zero-parallax plane, along the view axis
  RigPivot pivot = RigPivot::Centre;
  bool operator==(const StereoRig&) const = default;
};

const char* stereoModeName(StereoMode m);  // "off_axis", "parallel", "toe_in"
const char* rigPivotName(RigPivot p);      // "left", "centre", "right"
std::optional<RigPivot> rigPivotFromName(std::string_view s);

// A pinhole camera looking down its local -Z with +Y up (docs/architecture.md).
struct CameraModel {
  glm::dvec3 position{0.0};
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // camera to world
  double fovY = glm::radians(50.0);             // vertical field of view, radians
  double aspect = 16.0 / 9.0;                   // width / height of one eye's image
  double nearClip = 0.1;
  double farClip = 50000.0;
  double ndcShiftX = 0.0;  // horizontal NDC offset of the frustum (off-axis); ndc.x += ndcShiftX

  glm::dvec3 forward() const { return orientation * glm::dvec3(0, 0, -1); }
  glm::dvec3 right() const { return orientation * glm::dvec3(1, 0, 0); }
  glm::dvec3 up() const { return orientation * glm::dvec3(0, 1, 0); }
  // Reversed-Z projection, depth 1 at near and 0 at far (as render/ uses).
  glm::dmat4 projection() const;
  // World to camera, in double (callers subtract the eye for camera-relative floats).
  glm::dmat4 view() const;
  // NDC of a world point or of a world direction (a point at infinity);
  // nullopt behind the camera.
  std::optional<glm::dvec2> projectNdc(const glm::dvec3& world) const;
  std::optional<glm::dvec2> projectDirectionNdc(const glm::dvec3& worldDirection) const;
  // Pixel (origin top-left, x right, y down) in a width x height image.
  std::optional<glm::dvec2> projectPixel(const glm::dvec3& world, int width, int height) const;
  // The world point at NDC (x, y) and view depth `depth` (metres along -Z).
  glm::dvec3 unproject(const glm::dvec2& ndc, double depth) const;
};

struct StereoCameras {
  CameraModel left, right;
  StereoMode mode = StereoMode::OffAxis;
  // Things the user should know: toe-in's vertical parallax (with its size),
  // a convergence plane nearer than the near clip, a negative interaxial.
  std::vector<std::string> warnings;
};

// The two eyes. For every mode the eyes sit on the mono camera's right axis,
// `interaxial` apart, placed by the pivot. Off-axis: both keep the mono
// orientation and get ndcShiftX = -+ (b/2) / (C tan(fovX/2)), so any point
// on the plane at view depth C has the same NDC (the same pixel) in both
// eyes. Toe-in: each eye yaws inward by atan((b/2)/C), crossing on the rig's
// midline at depth C. Interaxial 0 gives two identical eyes.
StereoCameras stereoCameras(const CameraModel& mono, const StereoRig& rig);

// Screen parallax (right minus left, as a share of the image width; positive
// = behind the screen) of a point on the rig's midline at view depth
// `depth` (metres; infinity allowed). Off-axis: (b / (2 tan(fovX/2))) (1/C - 1/Z).
double midlineParallax(const StereoCameras& eyes, double depth);

}  // namespace hs::sequencer

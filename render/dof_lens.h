#pragma once
// The thin lens behind depth of field (docs/rendering.md "Depth of field"),
// GL-free: the circle of confusion of a depth, the largest one a view can
// show, the bad-input checks, and the lens-disc views of the reference.
//
// The camera's field of view is fixed (the renderer does not model focus
// breathing), so the image spans the same angle whatever the focus. The
// focal length is the one the camera already derives from that angle on its
// full-frame sensor (36 x 24 mm, the 24 mm height across the vertical field
// of view: scene::kSensorHeightMm, the `focal_length_mm` field), the
// aperture diameter is A = f / N, and a point at view depth z with the lens
// focused at s blurs into a disc of diameter, in pixels,
//   c(z) = A (1/s - 1/z) H / (2 tan(fovY / 2))
// (negative in front of the focus plane, positive behind). That is the thin
// lens's A f |z - s| / (z (s - f)) on a sensor at the focused image
// distance, scaled to the image height; it is also exactly the blur of
// averaging pinhole views from every point of an aperture disc of diameter
// A whose projections keep the focus plane fixed, which is what the
// reference renders (lensSampleView), so the reference and the post passes
// share one model.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render/render_view.h"

namespace hs::render {

struct DofLens {
  bool valid = false;        // a camera lens with usable values
  double focusDistance = 0;  // s, metres
  double focalLength = 0;    // f, metres (from the field of view)
  double aperture = 0;       // A = f / N, metres
  double cocScale = 0;       // pixels of CoC diameter per unit of (1/s - 1/z) in 1/m
  std::string problem;       // why a present lens was refused ("" otherwise)

  // Signed CoC diameter in pixels of a point at view depth z (metres; an
  // infinite z is the sky).
  double cocPixels(double z) const;
};

// The lens of `view` (none, with no problem, for a view that is no
// camera's). An f-stop that is not a positive finite number, or a focus
// distance that is not, is refused: the lens is invalid and `problem` names
// the camera and the field; the frame then renders without depth of field.
DofLens dofLensOf(const RenderView& view);

// The largest |CoC| in pixels over view depths [zNear, infinity) (the sky
// is always possible behind what is drawn).
double maxCocPixels(const DofLens& lens, double zNear);

// N points in the unit disc for the lens-averaged reference: stratified in
// area (Vogel's sunflower) and jittered within each stratum by a fixed-seed
// generator, so the same N always gives the same points.
std::vector<glm::dvec2> lensDiscSamples(int n, uint32_t seed = 0x5eed0dfu);

// The pinhole view from the point `disc` (unit disc) of the lens's aperture:
// the eye moved in the view's right/up plane by disc * A / 2, the projection
// sheared so that the focus plane projects where it did.
RenderView lensSampleView(const RenderView& view, const DofLens& lens, glm::dvec2 disc);

}  // namespace hs::render

#pragma once
// Red/cyan anaglyphs from a stereo pair, for checking stereo without a 3D
// display (the viewport preview and the "anaglyph" layout).
#include <optional>
#include <string_view>

#include "core/image.h"

namespace hs::sequencer {

enum class AnaglyphMethod : uint8_t {
  // Dubois' least-squares projection for red/cyan glasses (E. Dubois,
  // "Conversion of a Stereo Pair to Anaglyph with the Least-Squares
  // Projection Method", 2009), applied in linear light. The best colour
  // with the least ghosting for common glasses.
  Dubois,
  // Red from the left eye, green and blue from the right: full colour,
  // more retinal rivalry on saturated reds and cyans.
  Color,
  // Luminance of the left eye in red, of the right eye in green and blue:
  // no colour, least rivalry.
  Gray
};

const char* anaglyphMethodName(AnaglyphMethod m);  // "dubois", "color", "gray"

// The 3x3 matrices (row-major: output row r = sum over c of M[r][c] * input[c])
// applied to the left and right linear RGB.
struct AnaglyphMatrices {
  double left[3][3];
  double right[3][3];
};
const AnaglyphMatrices& anaglyphMatrices(AnaglyphMethod m);

// Same size and pixel kind (8-bit sRGB or float linear) in and out; an
// empty image if the eyes differ in size or kind. Alpha is opaque.
Image makeAnaglyph(const Image& left, const Image& right, AnaglyphMethod method = AnaglyphMethod::Dubois);

}  // namespace hs::sequencer

#include "sequencer/anaglyph.h"

#include <algorithm>

#include "core/srgb.h"

namespace hs::sequencer {

const char* anaglyphMethodName(AnaglyphMethod m) {
  switch (m) {
    case AnaglyphMethod::Dubois: return "dubois";
    case AnaglyphMethod::Color: return "color";
    case AnaglyphMethod::Gray: return "gray";
  }
  return "?";
}

const AnaglyphMatrices& anaglyphMatrices(AnaglyphMethod m) {
  // Dubois 2009, red/cyan. Each output row sums (left + right) to ~1, so
  // grey stays grey: white maps to (1.000, 0.999, 1.000).
  static const AnaglyphMatrices dubois{{{0.437, 0.449, 0.164}, {-0.062, -0.062, -0.024}, {-0.048, -0.050, -0.017}},
                                       {{-0.011, -0.032, -0.007}, {0.377, 0.761, 0.009}, {-0.026, -0.093, 1.234}}};
  static const AnaglyphMatrices color{{{1, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  // Rec. 709 luminance weights (the primaries of sRGB).
  static const AnaglyphMatrices gray{{{0.2126, 0.7152, 0.0722}, {0, 0, 0}, {0, 0, 0}},
                                     {{0, 0, 0}, {0.2126, 0.7152, 0.0722}, {0.2126, 0.7152, 0.0722}}};
  switch (m) {
    case AnaglyphMethod::Dubois: return dubois;
    case AnaglyphMethod::Color: return color;
    case AnaglyphMethod::Gray: return gray;
  }
  return dubois;
}

Image makeAnaglyph(const Image& left, const Image& right, AnaglyphMethod method) {
  if (left.width != right.width || left.height != right.height || left.isFloat() != right.isFloat() || left.empty())
    return {};
  float ml[3][3], mr[3][3];
  const AnaglyphMatrices& m = anaglyphMatrices(method);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) ml[r][c] = float(m.left[r][c]), mr[r][c] = float(m.right[r][c]);
  const size_t n = left.pixelCount();
  if (left.isFloat()) {
    Image out = Image::makeF(left.width, left.height);
    for (size_t i = 0; i < n; ++i) {
      const float* l = &left.rgbaF[i * 4];
      const float* rr = &right.rgbaF[i * 4];
      for (int r = 0; r < 3; ++r)
        out.rgbaF[i * 4 + size_t(r)] = std::max(0.0f, ml[r][0] * l[0] + ml[r][1] * l[1] + ml[r][2] * l[2] +
                                                           mr[r][0] * rr[0] + mr[r][1] * rr[1] + mr[r][2] * rr[2]);
      out.rgbaF[i * 4 + 3] = 1.0f;
    }
    return out;
  }
  Image out = Image::make8(left.width, left.height);
  for (size_t i = 0; i < n; ++i) {
    float l[3], rr[3];
    for (int c = 0; c < 3; ++c) {
      l[c] = srgb8ToLinear(left.rgba8[i * 4 + size_t(c)]);
      rr[c] = srgb8ToLinear(right.rgba8[i * 4 + size_t(c)]);
    }
    for (int r = 0; r < 3; ++r)
      out.rgba8[i * 4 + size_t(r)] = linearToSrgb8(ml[r][0] * l[0] + ml[r][1] * l[1] + ml[r][2] * l[2] +
                                                   mr[r][0] * rr[0] + mr[r][1] * rr[1] + mr[r][2] * rr[2]);
    out.rgba8[i * 4 + 3] = 255;
  }
  return out;
}

}  // namespace hs::sequencer

#include "core/srgb.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace hs {

float srgbFloatToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double linearToSrgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

float linearToSrgbFloat(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

namespace {

const std::array<float, 256>& toLinearTable() {
  static const std::array<float, 256> t = [] {
    std::array<float, 256> a{};
    for (int i = 0; i < 256; ++i) a[size_t(i)] = srgbFloatToLinear(float(i) / 255.0f);
    return a;
  }();
  return t;
}

// 16-bit linear -> 8-bit sRGB. 16 bits are enough: the steepest part of the
// curve (slope 12.92) moves 1/65535 of linear by 0.05 of an 8-bit step, so
// an 8-bit value taken to linear and back returns unchanged.
const std::vector<uint8_t>& toSrgbTable() {
  static const std::vector<uint8_t> t = [] {
    std::vector<uint8_t> a(65536);
    for (int i = 0; i < 65536; ++i)
      a[size_t(i)] = uint8_t(std::lround(linearToSrgbFloat(float(i) / 65535.0f) * 255.0f));
    return a;
  }();
  return t;
}

}  // namespace

float srgb8ToLinear(uint8_t v) { return toLinearTable()[v]; }

uint8_t linearToSrgb8(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  const float c = std::min(linear, 1.0f);
  return toSrgbTable()[size_t(std::lround(c * 65535.0f))];
}

}  // namespace hs

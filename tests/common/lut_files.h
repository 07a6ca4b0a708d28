#pragma once
// LUT files written by tests (scene/color_lut.h reads them through
// OpenColorIO): Resolve .cube 3D and 1D tables of a function, an identity,
// and a "look" that mixes the channels (so a wrong axis order or a missed
// interpolation shows).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>

#include <glm/glm.hpp>

namespace hs::test {

using LutFunction = std::function<glm::dvec3(glm::dvec3)>;

// A .cube 3D table of `f` with `size` points per axis (red fastest, as the format says).
inline std::string cube3dText(int size, const LutFunction& f) {
  std::string s = "TITLE \"test\"\n# written by a Hybridscape test\nLUT_3D_SIZE " + std::to_string(size) + "\n";
  char line[96];
  for (int b = 0; b < size; ++b)
    for (int g = 0; g < size; ++g)
      for (int r = 0; r < size; ++r) {
        const glm::dvec3 o = f(glm::dvec3(r, g, b) / double(size - 1));
        std::snprintf(line, sizeof line, "%.6f %.6f %.6f\n", o.r, o.g, o.b);
        s += line;
      }
  return s;
}

// A .cube 1D table (per channel) of `f`.
inline std::string cube1dText(int size, const LutFunction& f) {
  std::string s = "TITLE \"test 1D\"\nLUT_1D_SIZE " + std::to_string(size) + "\n";
  char line[96];
  for (int i = 0; i < size; ++i) {
    const glm::dvec3 o = f(glm::dvec3(double(i) / double(size - 1)));
    std::snprintf(line, sizeof line, "%.6f %.6f %.6f\n", o.r, o.g, o.b);
    s += line;
  }
  return s;
}

inline glm::dvec3 identityLook(glm::dvec3 c) { return c; }

// Warm highlights, cool shadows, a little cross-talk and contrast: every
// output depends on all three inputs.
inline glm::dvec3 tealOrangeLook(glm::dvec3 c) {
  const double l = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  const double s = l * l * (3.0 - 2.0 * l);  // an S curve on luminance
  glm::dvec3 o = c + (s - l) * 0.6;
  o += glm::dvec3(0.08, 0.02, -0.06) * (l - 0.45);
  o.r += 0.05 * std::sin(3.0 * c.b);
  return glm::clamp(o, 0.0, 1.0);
}

inline bool writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  return bool(out);
}

}  // namespace hs::test

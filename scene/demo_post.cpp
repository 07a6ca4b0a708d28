#include "scene/demo_post.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/content_hash.h"

namespace hs::scene {
namespace {

// Display code values in, out: luminance through a soft S curve, then the
// colour pushed towards amber in proportion to how bright it is and towards
// slate blue in the shadows, saturation kept.
glm::dvec3 duskLook(glm::dvec3 c) {
  const double l = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  const double curved = l + 0.35 * (l * l * (3.0 - 2.0 * l) - l);
  glm::dvec3 o = c + (curved - l);
  const glm::dvec3 amber(1.06, 0.99, 0.86), slate(0.95, 0.99, 1.06);
  o *= glm::mix(slate, amber, std::clamp(l * 1.4 - 0.1, 0.0, 1.0));
  return glm::clamp(o, 0.0, 1.0);
}

}  // namespace

std::string demoLutCube(int size) {
  std::string s = "TITLE \"Meteora dusk (Hybridscape demo)\"\nLUT_3D_SIZE " + std::to_string(size) + "\n";
  char line[80];
  for (int b = 0; b < size; ++b)
    for (int g = 0; g < size; ++g)
      for (int r = 0; r < size; ++r) {  // red fastest, as .cube has it
        const glm::dvec3 o = duskLook(glm::dvec3(r, g, b) / double(size - 1));
        std::snprintf(line, sizeof line, "%.6f %.6f %.6f\n", o.r, o.g, o.b);
        s += line;
      }
  return s;
}

void addDemoPost(SceneState& s) {
  s.settings.post.bloom = true;
  s.settings.post.bloomIntensity = 0.04f;
  s.settings.post.bloomThreshold = 1.0f;
  auto bytes = std::make_shared<const std::string>(demoLutCube());
  const uint64_t hash = contentHash(bytes->data(), bytes->size());
  s.settings.post.lut = LutData{"meteora_dusk.cube", std::move(bytes), hash};
  s.settings.post.lutEnabled = true;
  s.settings.post.lutIntensity = 0.7f;
}

}  // namespace hs::scene

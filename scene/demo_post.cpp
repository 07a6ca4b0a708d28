#include "scene/demo_post.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/content_hash.h"
#include "scene/ocio_config.h"

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

OcioConfigData demoOcioConfig() {
  // The film curve: scene light over [0, 32] (log2-spaced entries would
  // be kinder to the darks; 8192 linear ones keep them within 1/255), a
  // toe and a shoulder reaching display white at 32, sRGB-like encoding.
  constexpr int n = 8192;
  std::string lut = "Version 1\nFrom 0.0 32.0\nLength " + std::to_string(n) + "\nComponents 1\n{\n";
  char line[40];
  for (int i = 0; i < n; ++i) {
    const double x = 32.0 * i / (n - 1);
    const double shoulder = x * (1.0 + x / (32.0 * 32.0)) / (1.0 + x);  // extended Reinhard, 1 at 32
    const double toe = shoulder * shoulder / (shoulder + 0.02) * 1.02;   // deeper darks, 1 still 1
    std::snprintf(line, sizeof line, "  %.7f\n", std::pow(std::clamp(toe, 0.0, 1.0), 1.0 / 2.2));
    lut += line;
  }
  lut += "}\n";
  const std::string config =
      "ocio_profile_version: 2\n"
      "description: Hybridscape demo - a film view for the Meteora valley\n"
      "search_path: luts\n"
      "roles:\n  default: raw\n  scene_linear: linear\n"
      "file_rules:\n  - !<Rule> {name: Default, colorspace: default}\n"
      "displays:\n  sRGB:\n"
      "    - !<View> {name: Film, colorspace: film}\n"
      "    - !<View> {name: Raw, colorspace: raw}\n"
      "active_displays: [sRGB]\nactive_views: [Film, Raw]\n"
      "colorspaces:\n"
      "  - !<ColorSpace> {name: linear, isdata: false}\n"
      "  - !<ColorSpace> {name: raw, isdata: true}\n"
      "  - !<ColorSpace>\n    name: film\n    isdata: false\n"
      "    from_reference: !<FileTransform> {src: meteora_film.spi1d, interpolation: linear}\n";
  OcioConfigData out;
  out.fileName = "meteora_film.ocio";
  for (auto [path, text] : {std::pair<std::string, std::string>{"config.ocio", config},
                            std::pair<std::string, std::string>{"search0/meteora_film.spi1d", lut}}) {
    auto bytes = std::make_shared<const std::string>(std::move(text));
    const uint64_t hash = contentHash(bytes->data(), bytes->size());
    out.files.push_back({path, std::move(bytes), hash});
  }
  out.contentHash = ocioBundleHash(out.files);
  return out;
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
  s.settings.post.ocioConfig = demoOcioConfig();  // stored, off: the Post dock turns it on
}

}  // namespace hs::scene

#include "render/export_job_tag.h"

#include <cstdio>

#include "scene/scene_json.h"

namespace hs::render {

namespace {

// FNV-1a, 64 bit: stable across machines and runs (std::hash is not).
uint64_t fnv1a(const std::string& text, uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string exportJobTag(const scene::SceneState& scene, scene::EntityId camera,
                         const sequencer::ExportSettings& s, const StereoFrameOptions& o) {
  std::string settings = "camera=" + std::to_string(camera) + ";eye=" + std::to_string(s.eyeWidth) + "x" +
                         std::to_string(s.eyeHeight) + ";layout=" + sequencer::layoutName(s.layout) +
                         ";anaglyph=" + std::to_string(int(s.anaglyph)) + ";grid=" + (o.showGrid ? "1" : "0") +
                         ";bits16=" + (o.displayBits16 ? "1" : "0") + ";png16=" + (s.image.png16 ? "1" : "0") +
                         ";jpeg=" + std::to_string(s.image.jpegQuality) +
                         ";pngz=" + std::to_string(s.image.pngCompression) +
                         ";rate=" + std::to_string(s.rate.num) + "/" + std::to_string(s.rate.den);
  // What an import said (its timing, its warnings) and where an asset came
  // from do not change a pixel; the content hash that names the mesh does.
  scene::SceneState pixels = scene;
  for (auto& [id, asset] : pixels.assets) {
    asset.importReport = nullptr;
    asset.sourcePath.clear();
  }
  const uint64_t h = fnv1a(settings, fnv1a(scene::canonicalJson(pixels)));
  char out[32];
  std::snprintf(out, sizeof out, "hs1-%016llx", static_cast<unsigned long long>(h));
  return out;
}

}  // namespace hs::render

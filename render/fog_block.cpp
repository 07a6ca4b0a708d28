#include "render/fog_block.h"

namespace hs::render {

std::vector<std::string> fogDefines(const scene::SceneSettings& s) {
  switch (s.fogMode) {
    case scene::FogMode::None: return {};
    case scene::FogMode::DepthCue: return {"FOG_DEPTH_CUE"};
    case scene::FogMode::ExponentialHeight: return {"FOG_HEIGHT"};
  }
  return {};
}

FogBlock fogBlock(const scene::SceneSettings& s, double originZ) {
  FogBlock b;
  b.colour = glm::vec4(s.fogColour, 0.0f);
  b.params = glm::vec4(s.fogK1, s.fogK2, s.fogDensity, s.fogHeightFalloff);
  b.height = glm::vec4(float(double(s.fogHeight) - originZ), 0.0f, 0.0f, 0.0f);
  return b;
}

}  // namespace hs::render

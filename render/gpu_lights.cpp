#include "render/gpu_lights.h"

#include <algorithm>

namespace hs::render {

GpuLight gpuLight(const WorldLight& l, const glm::dvec3& origin) {
  GpuLight g;
  g.position = glm::vec4(glm::vec3(l.position - origin), l.range);
  g.color = glm::vec4(l.color, l.type == scene::Light::Type::Spot ? 2.0f : 1.0f);
  g.direction = glm::vec4(glm::vec3(l.direction), 0.0f);
  // Filament's spot: attenuation = saturate(cos · scale + offset), 0 at the
  // outer cone, 1 from the inner one in. The floor keeps equal cones (a hard
  // edge) finite.
  const float scale = 1.0f / std::max(l.cosInnerHalf - l.cosOuterHalf, 1e-4f);
  g.spot = glm::vec4(scale, -l.cosOuterHalf * scale, 0.0f, 0.0f);
  return g;
}

}  // namespace hs::render

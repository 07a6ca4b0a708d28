#include "render/passes/environment_pass.h"

#include "render/environment_maps.h"

namespace hs::render {
namespace {
struct EnvironmentData {};
}  // namespace

void addEnvironmentPass(FrameGraph& graph, FrameContext& frame) {
  EnvironmentMaps& env = frame.res.environment;
  if (frame.settings.sky != scene::SkyModel::Analytic) {
    env.release(frame.res.pool);
    return;
  }
  // The sun the lights use (RenderWorld: the first visible sun); its
  // direction of travel reversed points at it.
  const glm::dvec3 sunDir = frame.world.sun ? -frame.world.sun->direction : glm::dvec3(0.0);
  const EnvironmentKey key{sunDir, frame.settings.skyTurbidity, frame.settings.skyGroundAlbedo};
  if (!env.prepare(key)) {
    env.bind();
    return;
  }
  graph.addPass<EnvironmentData>(
      "environment", [](PassBuilder& b, EnvironmentData&) { b.sideEffect(); },  // writes the persistent maps
      [&frame](const EnvironmentData&, const PassResources&) {
        frame.res.environment.update(frame.res);
        frame.res.environment.bind();
      });
}

}  // namespace hs::render

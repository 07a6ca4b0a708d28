#include "scene/demo_lights.h"

#include "sequencer/camera_path.h"

namespace hs::scene {
namespace {

EntityId addLight(SceneState& s, const std::string& name, glm::dvec3 at, const Light& l,
                  glm::dvec3 aim = glm::dvec3(0.0)) {
  Entity e;
  e.id = s.maxEntityId() + 1;
  e.name = name;
  e.transform.translation = at;
  // A spot shines along local −Z, the way a camera looks.
  if (l.type == Light::Type::Spot) e.transform.rotation = sequencer::lookRotation(aim - at);
  e.light = l;
  s.entities.emplace(e.id, e);
  s.roots.push_back(e.id);
  return e.id;
}

}  // namespace

void addDemoLights(SceneState& s) {
  // Warm, from the front and above, onto the big bunny: about 90 000 lux
  // where it lands 6.5 m away (as bright as the sun).
  Light spot;
  spot.type = Light::Type::Spot;
  spot.color = {1.0f, 0.72f, 0.42f};
  spot.intensity = 1.5e6f;  // lumens into a 40° cone: 4 million candela
  spot.range = 25.0f;
  spot.innerConeDeg = 22.0f;
  spot.outerConeDeg = 40.0f;
  addLight(s, "Lantern (spot)", {1.5, -4.5, 4.5}, spot, {0.0, 0.0, 1.0});

  // Two point lights by the small bunnies, each about 60% of the sun 2 m
  // away.
  Light blue;
  blue.type = Light::Type::Point;
  blue.color = {0.45f, 0.65f, 1.0f};
  blue.intensity = 3.0e6f;
  blue.range = 9.0f;
  addLight(s, "Lamp (blue)", {-2.4, -0.4, 1.6}, blue);
  Light amber = blue;
  amber.color = {1.0f, 0.55f, 0.25f};
  addLight(s, "Lamp (amber)", {2.6, 0.4, 1.8}, amber);

  // Depth cueing: half the colour kept 400 m away, the valley's far side
  // fading into a haze the colour of the horizon.
  s.settings.fogMode = FogMode::DepthCue;
  s.settings.fogColour = s.settings.skyHorizon;
  s.settings.fogK1 = 1.0f;
  s.settings.fogK2 = 1.0f / 400.0f;
}

}  // namespace hs::scene

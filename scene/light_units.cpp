#include "scene/light_units.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "scene/fields.h"
#include "scene/object_tracks.h"
#include "scene/scene_state.h"

namespace hs::scene {

double sceneUnitsPerNit() { return 1.0 / (1.2 * std::exp2(kReferenceEv100)); }

double exposureMultiplier(float ev100) { return std::exp2(double(float(kReferenceEv100)) - double(ev100)); }

double luminousIntensityCandela(const Light& l) {
  const double pi = glm::pi<double>();
  switch (l.type) {
    case Light::Type::Sun: return l.intensity;
    case Light::Type::Point: return double(l.intensity) / (4.0 * pi);
    case Light::Type::Spot: {
      // The outer cone's solid angle, 2π(1 − cos θ) for the half angle θ.
      // Field ranges keep the cone in (0, 180) degrees; the floor keeps a
      // degenerate cone finite.
      const double half = glm::radians(double(l.outerConeDeg)) * 0.5;
      return double(l.intensity) / std::max(2.0 * pi * (1.0 - std::cos(half)), 1e-9);
    }
  }
  return 0.0;
}

glm::vec3 lightRadiometricColor(const Light& l) {
  return l.color * float(luminousIntensityCandela(l) * sceneUnitsPerNit());
}

double legacyLightIntensity(Light::Type type, double oldIntensity) {
  // The old value was the shader's result on a white surface facing the
  // light (no 1/π); the shader now divides by π, so the light takes it back.
  const double lux = oldIntensity * glm::pi<double>() / sceneUnitsPerNit();
  return type == Light::Type::Sun ? lux : 4.0 * glm::pi<double>() * lux;
}

double legacyExposureEv100(double oldMultiplier) {
  return kReferenceEv100 - std::log2(std::max(oldMultiplier, 1e-30));
}

void migrateToPhysicalLightUnits(SceneState& state, std::optional<double> oldExposure) {
  for (auto& [id, e] : state.entities) {
    if (!e.light) continue;
    const double scale = legacyLightIntensity(e.light->type, 1.0);
    e.light->intensity = float(legacyLightIntensity(e.light->type, e.light->intensity));
    // Scaling a curve's values and slopes alike scales the whole curve.
    if (sequencer::Binding* b = state.sequence.findBinding(id)) {
      for (sequencer::Track& t : b->tracks) {
        auto* track = std::get_if<sequencer::ScalarTrack>(&t);
        if (!track || track->property != "light.intensity") continue;
        for (sequencer::ScalarKey& k : track->keys) {
          k.value *= scale;
          k.inSlope *= scale;
          k.outSlope *= scale;
        }
      }
    }
  }
  if (oldExposure) {
    const SettingsField* f = findSettingsField("exposure_ev100");
    f->set(state.settings, FieldValue(legacyExposureEv100(*oldExposure)));  // clamped to the field's range
  }
}

void migrateToPhysicalBrdf(SceneState& state) {
  const SettingsField* f = findSettingsField("exposure_ev100");
  const double ev = std::get<double>(f->get(state.settings));
  f->set(state.settings, FieldValue(ev - kLog2Pi));  // clamped to the field's range
  // A shift moves a curve's values and leaves its slopes as they are.
  if (sequencer::Binding* b = state.sequence.findBinding(settingsTarget())) {
    for (sequencer::Track& t : b->tracks) {
      auto* track = std::get_if<sequencer::ScalarTrack>(&t);
      if (!track || track->property != std::string(kSettingsTrackPrefix) + f->key) continue;
      for (sequencer::ScalarKey& k : track->keys) k.value = std::clamp(k.value - kLog2Pi, f->min, f->max);
    }
  }
}

}  // namespace hs::scene

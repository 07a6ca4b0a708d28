#pragma once
// Physical light units and exposure (docs/rendering.md "Lights and
// exposure"). Lights are set in lux (sun) and lumens (point, spot), the
// camera in EV100, as in Filament and Unreal. The renderer works in "scene
// units": luminance pre-exposed at the reference EV100 below, so a noon sun
// lands near today's values of 1-3 in the HDR buffer (half floats would
// overflow at cd/m²), and the tone mapper multiplies by 2^(reference − EV100).
#include <optional>

#include "scene/components.h"

namespace hs::scene {

// The exposure at which one scene unit is 1.2 · 2^15.2 ≈ 45 168 cd/m²
// (Filament's saturation-based exposure, 1 / (1.2 · 2^EV100)). It was chosen
// so that a 100 000 lux sun at EV100 15.2 looks as the default sun did
// before the units were physical (within 0.7%).
constexpr double kReferenceEv100 = 15.2;
double sceneUnitsPerNit();  // 1 / (1.2 · 2^kReferenceEv100)

// Multiplier the tone mapper applies: 2^(kReferenceEv100 − ev100), exactly
// 1 at the settings' default (a float, as SceneSettings holds it).
double exposureMultiplier(float ev100);

// Luminous intensity (candela) of a point or spot light from its power
// (components.h: I = Φ/4π, spot I = Φ / (2π(1 − cos(outer/2)))); a sun's
// illuminance in lux is returned as it is.
double luminousIntensityCandela(const Light& l);

// What a light contributes in scene units: colour × illuminance (sun) or
// colour × intensity in candela (point, spot; the renderer divides by d²).
glm::vec3 lightRadiometricColor(const Light& l);

// Files before format 6 (scene_json.h) held intensities and exposure in
// the old relative units; these give the values that render the same.
//   sun:          lux = old × 1.2 · 2^kReferenceEv100
//   point:        lumens = 4π × old × 1.2 · 2^kReferenceEv100 (old: at 1 m)
//   exposure:     EV100 = kReferenceEv100 − log2(old multiplier)
double legacyLightIntensity(Light::Type type, double oldIntensity);
double legacyExposureEv100(double oldMultiplier);

// Converts a scene read from a file before format 6: every light's
// intensity, the keys (values and slopes) of "light.intensity" tracks, and
// the exposure multiplier (`oldExposure`, the file's settings.exposure;
// nullopt: the old default 1).
struct SceneState;
void migrateToPhysicalLightUnits(SceneState& state, std::optional<double> oldExposure);

}  // namespace hs::scene

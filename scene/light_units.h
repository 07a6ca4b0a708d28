#pragma once
// Physical light units and exposure (docs/rendering.md "Lights and
// exposure"). Lights are set in lux (sun) and lumens (point, spot), the
// camera in EV100, as in Filament and Unreal. The renderer works in "scene
// units": luminance (cd/m²) pre-exposed at the reference EV100 below, so a
// noon sun on a white surface lands near 2 in the HDR buffer (half floats
// would overflow at cd/m²), and the tone mapper multiplies by
// 2^(reference − EV100). The lighting models return physical radiance (a
// white Lambert surface facing a light of illuminance E returns E/π,
// shaders/brdf.glsl), and the sky's luminance meets the same unit
// (render/sky_model.h).
#include <optional>

#include "scene/components.h"

namespace hs::scene {

// The exposure at which one scene unit is 1.2 · 2^EV100 ≈ 14 378 cd/m²
// (Filament's saturation-based exposure, 1 / (1.2 · 2^EV100)). It is
// 15.2 − log2 π ≈ 13.5485: when the shaders took up the BRDF's 1/π (format
// 8), the reference moved by log2 π so that a light's result in scene
// units stayed what it was (lux/π · 1/(1.2 · 2^13.5485) = lux · 1/(1.2 ·
// 2^15.2)). 15.2 itself was chosen so that a 100 000 lux sun looks as the
// default sun did before the units were physical (within 0.7%). It is also
// the settings' default exposure.
inline constexpr double kLog2Pi = 1.6514961294723187;  // log2(π)
constexpr double kReferenceEv100 = 15.2 - kLog2Pi;
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
// the old relative units; these give the values that render the same. An
// old intensity was the light's scene-unit value with no 1/π applied, so
// the lux (candela) that give it back through a shader that divides by π
// are π / sceneUnitsPerNit() times it (= 1.2 · 2^15.2, as since format 6):
//   sun:          lux = old × π / sceneUnitsPerNit()
//   point:        lumens = 4π × old × π / sceneUnitsPerNit() (old: at 1 m)
//   exposure:     EV100 = kReferenceEv100 − log2(old multiplier)
double legacyLightIntensity(Light::Type type, double oldIntensity);
double legacyExposureEv100(double oldMultiplier);

// Converts a scene read from a file before format 6: every light's
// intensity, the keys (values and slopes) of "light.intensity" tracks, and
// the exposure multiplier (`oldExposure`, the file's settings.exposure;
// nullopt: the old default 1).
struct SceneState;
void migrateToPhysicalLightUnits(SceneState& state, std::optional<double> oldExposure);

// Converts a scene read from a file of format 6 or 7, whose shaders folded
// the BRDF's 1/π into the lights (scene_json.h): the lights keep their lux
// and lumens, and the exposure (settings.exposure_ev100 and every key of a
// "settings.exposure_ev100" track) moves by −log2 π, so the frame is the
// same. Values land in the field's range (a key or value below −10 + log2
// π is held at −10).
void migrateToPhysicalBrdf(SceneState& state);

}  // namespace hs::scene

#pragma once
// Ready emitters for the film's effects (docs/particles.md, "Presets"):
// snow, a fog bank, a torch (flame and smoke), a campfire (flames, smoke,
// embers) and dust. Each returns plain EmitterDescs that pass validate();
// the options are those of `hybridscape-cli particles add PRESET SCENE
// [--name N] [--at x,y,z] [--area x0,y0,x1,y1] [--rate R] [--seed S]`.
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "particles/emitter.h"

namespace hs::particles {

struct PresetOptions {
  std::string name{};                   // empty: the preset's name ("Snow"); several emitters get "Name flame", ...
  glm::dvec3 at{0.0};                   // world position (the area's ground level for snow, fog and dust)
  std::optional<glm::dvec4> area{};     // x0, y0, x1, y1 (world): snow, fog and dust cover it; default 100 m around `at`
  std::optional<double> rate{};         // particles per second of the main emitter (others scale with it)
  uint32_t seed = 1;
};

std::vector<EmitterDesc> snowPreset(const PresetOptions& o = {});
std::vector<EmitterDesc> fogBankPreset(const PresetOptions& o = {});
std::vector<EmitterDesc> torchPreset(const PresetOptions& o = {});     // flame + smoke
std::vector<EmitterDesc> campfirePreset(const PresetOptions& o = {});  // flames + smoke + embers
std::vector<EmitterDesc> dustPreset(const PresetOptions& o = {});

// "snow", "fog", "torch", "campfire", "dust".
const std::vector<std::string>& presetNames();
// The preset by name; empty with `error` listing the names for an unknown one.
std::vector<EmitterDesc> makePreset(std::string_view name, const PresetOptions& o, std::string& error);

}  // namespace hs::particles

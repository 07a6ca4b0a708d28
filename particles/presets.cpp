// The presets. Values are chosen for the Meteora film at 60 fps: sizes in
// metres, rates per second; snow falls at about 1 m/s (drag 8/s: terminal
// speed g/k = 1.2 m/s), flames rise on a buoyancy of +2..3 m/s^2 against
// drag, smoke spreads as it rises.
#include "particles/presets.h"

#include <cmath>

#include <glm/vec2.hpp>

namespace hs::particles {

namespace {

std::string nameOr(const PresetOptions& o, const char* def) { return o.name.empty() ? std::string(def) : o.name; }

// The area's centre (at ground level `at.z`) and half size.
void areaOf(const PresetOptions& o, glm::dvec3& centre, glm::dvec2& half) {
  if (o.area) {
    const glm::dvec4 a = *o.area;
    centre = {0.5 * (a.x + a.z), 0.5 * (a.y + a.w), o.at.z};
    half = {0.5 * std::abs(a.z - a.x), 0.5 * std::abs(a.w - a.y)};
  } else {
    centre = o.at;
    half = {50.0, 50.0};
  }
}

EmitterDesc base(const std::string& name, const PresetOptions& o, uint32_t salt) {
  EmitterDesc e;
  e.name = name;
  e.seed = o.seed * 2654435761U + salt;
  e.origin = o.at;
  e.start = -60.0;  // already running when the shot starts
  return e;
}

}  // namespace

std::vector<EmitterDesc> snowPreset(const PresetOptions& o) {
  glm::dvec3 c;
  glm::dvec2 half;
  areaOf(o, c, half);
  EmitterDesc e = base(nameOr(o, "Snow"), o, 1);
  const double area = 4.0 * half.x * half.y;
  e.origin = c + glm::dvec3(0, 0, 30.0);
  e.shape = Shape::Box;
  e.boxHalf = {half.x, half.y, 2.0};
  e.rate = o.rate.value_or(std::min(1e6, 0.2 * area));  // 0.2 flakes per m^2 per second
  e.maxLive = 1000000;
  e.direction = {0, 0, -1};
  e.spreadDeg = 20;
  e.speedMin = 0.5, e.speedMax = 1.2;
  e.lifetimeMin = 30.0, e.lifetimeMax = 40.0;
  e.sizeMin = 0.01, e.sizeMax = 0.025;
  e.rotationMinDeg = -180, e.rotationMaxDeg = 180;
  e.spinMinDegPerS = -90, e.spinMaxDegPerS = 90;
  e.gravity = {0, 0, -9.81};
  e.drag = 8.0;
  e.wind = {1.0, 0.3, 0.0};
  e.turbulence = 1.5;
  e.turbulenceFrequency = 0.3;
  e.turbulenceEvolution = 0.2;
  e.collision = CollisionMode::Stick;
  e.replayStep = 1.0 / 30.0;
  e.colourOverLife.keys = {{0.0, {1, 1, 1, 0}}, {0.05, {1, 1, 1, 0.9}}, {0.9, {1, 1, 1, 0.9}}, {1.0, {1, 1, 1, 0}}};
  e.sprite = Sprite::Snowflake;
  e.softDistance = 0.1;
  return {e};
}

std::vector<EmitterDesc> fogBankPreset(const PresetOptions& o) {
  glm::dvec3 c;
  glm::dvec2 half;
  areaOf(o, c, half);
  EmitterDesc e = base(nameOr(o, "Fog bank"), o, 2);
  e.origin = c + glm::dvec3(0, 0, 3.0);
  e.shape = Shape::Box;
  e.boxHalf = {half.x, half.y, 2.0};
  e.rate = o.rate.value_or(std::min(1e4, 0.002 * 4.0 * half.x * half.y));
  e.direction = {1, 0, 0};
  e.spreadDeg = 180;
  e.speedMin = 0.0, e.speedMax = 0.15;
  e.lifetimeMin = 20.0, e.lifetimeMax = 30.0;
  e.sizeMin = 4.0, e.sizeMax = 9.0;
  e.rotationMinDeg = -180, e.rotationMaxDeg = 180;
  e.spinMinDegPerS = -3, e.spinMaxDegPerS = 3;
  e.gravity = glm::dvec3(0.0);
  e.drag = 0.5;
  e.wind = {0.4, 0.1, 0.0};
  e.sizeOverLife.keys = {{0.0, 0.7}, {1.0, 1.3}};
  e.colourOverLife.keys = {{0.0, {0.85, 0.87, 0.9, 0}}, {0.3, {0.85, 0.87, 0.9, 0.22}}, {0.7, {0.85, 0.87, 0.9, 0.22}},
                           {1.0, {0.85, 0.87, 0.9, 0}}};
  e.sprite = Sprite::Smoke;
  e.softDistance = 5.0;  // a bank meets the ground and the pillars without a seam
  return {e};
}

namespace {

EmitterDesc flame(const std::string& name, const PresetOptions& o, uint32_t salt, double rate, double radius,
                  double size) {
  EmitterDesc e = base(name, o, salt);
  e.shape = Shape::Disc;
  e.radius = radius;
  e.rate = rate;
  e.direction = {0, 0, 1};
  e.spreadDeg = 10;
  e.speedMin = 0.3, e.speedMax = 0.7;
  e.lifetimeMin = 0.35, e.lifetimeMax = 0.7;
  e.sizeMin = size, e.sizeMax = 1.6 * size;
  e.rotationMinDeg = -20, e.rotationMaxDeg = 20;
  e.gravity = {0, 0, 3.0};  // buoyancy
  e.drag = 3.0;
  e.wind = {0.2, 0.0, 0.0};
  e.turbulence = 2.0;
  e.turbulenceFrequency = 3.0;
  e.turbulenceEvolution = 2.0;
  e.replayStep = 1.0 / 120.0;
  e.flipbookFrames = 16;
  e.sizeOverLife.keys = {{0.0, 0.6}, {0.2, 1.0}, {1.0, 0.25}};
  e.colourOverLife.keys = {{0.0, {6.0, 3.0, 0.8, 0.0}}, {0.1, {6.0, 3.0, 0.8, 1.0}}, {0.6, {3.0, 0.9, 0.15, 0.7}},
                           {1.0, {1.0, 0.2, 0.02, 0.0}}};
  e.sprite = Sprite::Flame;
  e.blend = Blend::Additive;
  e.lit = false;
  e.softDistance = 0.2;
  return e;
}

EmitterDesc smoke(const std::string& name, const PresetOptions& o, uint32_t salt, double rate, double lift,
                  double size) {
  EmitterDesc e = base(name, o, salt);
  e.origin = o.at + glm::dvec3(0, 0, lift);
  e.shape = Shape::Sphere;
  e.radius = 0.5 * size;
  e.rate = rate;
  e.direction = {0, 0, 1};
  e.spreadDeg = 15;
  e.speedMin = 0.4, e.speedMax = 0.9;
  e.lifetimeMin = 3.0, e.lifetimeMax = 6.0;
  e.sizeMin = size, e.sizeMax = 2.0 * size;
  e.rotationMinDeg = -180, e.rotationMaxDeg = 180;
  e.spinMinDegPerS = -20, e.spinMaxDegPerS = 20;
  e.gravity = {0, 0, 1.2};
  e.drag = 1.0;
  e.wind = {0.8, 0.2, 0.0};
  e.turbulence = 0.6;
  e.turbulenceFrequency = 0.8;
  e.turbulenceEvolution = 0.5;
  e.replayStep = 1.0 / 60.0;
  e.sizeOverLife.keys = {{0.0, 0.5}, {1.0, 3.0}};
  e.colourOverLife.keys = {{0.0, {0.25, 0.24, 0.23, 0.0}}, {0.15, {0.25, 0.24, 0.23, 0.45}}, {1.0, {0.4, 0.4, 0.4, 0.0}}};
  e.sprite = Sprite::Smoke;
  e.softDistance = 0.5;
  return e;
}

}  // namespace

std::vector<EmitterDesc> torchPreset(const PresetOptions& o) {
  const std::string n = nameOr(o, "Torch");
  const double rate = o.rate.value_or(80.0);
  return {flame(n + " flame", o, 3, rate, 0.05, 0.12), smoke(n + " smoke", o, 4, rate * 0.15, 0.35, 0.15)};
}

std::vector<EmitterDesc> campfirePreset(const PresetOptions& o) {
  const std::string n = nameOr(o, "Campfire");
  const double rate = o.rate.value_or(200.0);
  EmitterDesc embers = base(n + " embers", o, 7);
  embers.shape = Shape::Disc;
  embers.radius = 0.3;
  embers.rate = rate * 0.08;
  embers.direction = {0, 0, 1};
  embers.spreadDeg = 25;
  embers.speedMin = 1.0, embers.speedMax = 3.5;
  embers.lifetimeMin = 1.0, embers.lifetimeMax = 2.5;
  embers.sizeMin = 0.008, embers.sizeMax = 0.02;
  embers.gravity = {0, 0, -1.0};  // light: buoyancy nearly cancels gravity
  embers.drag = 0.8;
  embers.wind = {0.6, 0.0, 0.0};
  embers.turbulence = 4.0;
  embers.turbulenceFrequency = 1.5;
  embers.turbulenceEvolution = 1.0;
  embers.collision = CollisionMode::Kill;
  embers.replayStep = 1.0 / 120.0;
  embers.colourOverLife.keys = {{0.0, {8.0, 3.0, 0.6, 1.0}}, {0.7, {4.0, 1.0, 0.1, 1.0}}, {1.0, {1.0, 0.1, 0.0, 0.0}}};
  embers.sprite = Sprite::Spark;
  embers.blend = Blend::Additive;
  embers.facing = Facing::Velocity;
  embers.lit = false;
  embers.softDistance = 0.0;
  return {flame(n + " flames", o, 5, rate, 0.4, 0.3), smoke(n + " smoke", o, 6, rate * 0.1, 0.9, 0.4), embers};
}

std::vector<EmitterDesc> dustPreset(const PresetOptions& o) {
  glm::dvec3 c;
  glm::dvec2 half;
  areaOf(o, c, half);
  EmitterDesc e = base(nameOr(o, "Dust"), o, 8);
  e.origin = c + glm::dvec3(0, 0, 0.3);
  e.shape = Shape::Box;
  e.boxHalf = {half.x, half.y, 0.3};
  e.rate = o.rate.value_or(std::min(1e4, 0.01 * 4.0 * half.x * half.y));
  e.direction = {0, 0, 1};
  e.spreadDeg = 60;
  e.speedMin = 0.2, e.speedMax = 0.6;
  e.lifetimeMin = 4.0, e.lifetimeMax = 8.0;
  e.sizeMin = 0.5, e.sizeMax = 1.5;
  e.rotationMinDeg = -180, e.rotationMaxDeg = 180;
  e.spinMinDegPerS = -10, e.spinMaxDegPerS = 10;
  e.gravity = {0, 0, -0.3};
  e.drag = 1.0;
  e.wind = {2.0, 0.3, 0.0};
  e.turbulence = 0.5;
  e.turbulenceFrequency = 0.4;
  e.replayStep = 1.0 / 30.0;
  e.sizeOverLife.keys = {{0.0, 0.5}, {1.0, 1.5}};
  e.colourOverLife.keys = {{0.0, {0.62, 0.52, 0.38, 0}}, {0.3, {0.62, 0.52, 0.38, 0.3}}, {1.0, {0.62, 0.52, 0.38, 0}}};
  e.sprite = Sprite::Smoke;
  e.softDistance = 1.0;
  return {e};
}

const std::vector<std::string>& presetNames() {
  static const std::vector<std::string> n = {"snow", "fog", "torch", "campfire", "dust"};
  return n;
}

std::vector<EmitterDesc> makePreset(std::string_view name, const PresetOptions& o, std::string& error) {
  if (name == "snow") return snowPreset(o);
  if (name == "fog") return fogBankPreset(o);
  if (name == "torch") return torchPreset(o);
  if (name == "campfire") return campfirePreset(o);
  if (name == "dust") return dustPreset(o);
  error = "no particle preset '" + std::string(name) + "' (presets: snow, fog, torch, campfire, dust)";
  return {};
}

}  // namespace hs::particles

// EmitterDesc: the declarations, the field table, validation and JSON.
#include "particles/emitter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/world_extent.h"

namespace hs::particles {

namespace {

Json vec3Json(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }
glm::dvec3 jsonVec3(const Json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }
Json pairJson(double a, double b) { return Json::array({a, b}); }

constexpr const char* kShapes[] = {"point", "box", "sphere", "disc", "cone", "mesh", "terrain"};
constexpr const char* kCollisions[] = {"none", "bounce", "kill", "stick"};
constexpr const char* kSprites[] = {"snowflake", "smoke", "flame", "spark"};
constexpr const char* kBlends[] = {"alpha", "additive"};
constexpr const char* kFacings[] = {"camera", "velocity"};
constexpr const char* kSpaces[] = {"local", "world"};

template <class E, size_t N>
E enumFrom(const char* const (&names)[N], const std::string& s) {
  for (size_t i = 0; i < N; ++i)
    if (s == names[i]) return E(i);
  return E(0);
}

std::string prefix(const EmitterDesc& e, std::string_view field) {
  return "emitter '" + e.name + "', field '" + std::string(field) + "': ";
}

}  // namespace

const char* shapeName(Shape s) { return kShapes[int(s)]; }
const char* collisionName(CollisionMode c) { return kCollisions[int(c)]; }
const char* spriteName(Sprite s) { return kSprites[int(s)]; }
const char* blendName(Blend b) { return kBlends[int(b)]; }
const char* facingName(Facing f) { return kFacings[int(f)]; }
const char* spaceName(Space s) { return kSpaces[int(s)]; }

bool emitterKeyAddedAfter(std::string_view key, int formatVersion) {
  // Keys each scene format added to the emitter (format 10 was the first).
  struct Added {
    std::string_view key;
    int since;
  };
  static constexpr Added kAdded[] = {{"space", 11}, {"draw_mesh", 11}};
  for (const Added& a : kAdded)
    if (a.key == key) return formatVersion < a.since;
  return false;
}

double Curve::eval(double t, double fallback) const {
  if (keys.empty()) return fallback;
  if (t <= keys.front().t) return keys.front().value;
  if (t >= keys.back().t) return keys.back().value;
  const auto it = std::upper_bound(keys.begin(), keys.end(), t, [](double x, const CurveKey& k) { return x < k.t; });
  const CurveKey& b = *it;
  const CurveKey& a = *(it - 1);
  const double s = (t - a.t) / (b.t - a.t);
  return a.value + (b.value - a.value) * s;
}

glm::dvec4 ColourCurve::eval(double t) const {
  if (keys.empty()) return glm::dvec4(1.0);
  if (t <= keys.front().t) return keys.front().rgba;
  if (t >= keys.back().t) return keys.back().rgba;
  const auto it = std::upper_bound(keys.begin(), keys.end(), t, [](double x, const ColourKey& k) { return x < k.t; });
  const ColourKey& b = *it;
  const ColourKey& a = *(it - 1);
  const double s = (t - a.t) / (b.t - a.t);
  return a.rgba + (b.rgba - a.rgba) * s;
}

double EmitterDesc::rateAt(double t) const {
  if (!(t >= start && t <= start + duration)) return 0.0;
  return std::max(0.0, rateKeys.eval(t, rate));
}

const std::vector<ParamDecl>& emitterParamDecls() {
  static const std::vector<ParamDecl> decls = [] {
    const EmitterDesc d;
    const double W = kWorldExtentMetres;
    const std::string gWhen = "emission", gStart = "initial state", gForce = "forces", gHit = "collision",
                      gLook = "appearance";
    return std::vector<ParamDecl>{
        {.key = "seed", .label = "Seed", .min = 0, .max = 4294967295.0, .integer = true, .defaultValue = d.seed,
         .help = "the counter-based hash's seed: another seed, other particles", .editor = true, .decimals = 0},
        {.key = "origin_m", .label = "Origin", .unit = Unit::Metres, .min = -W, .max = W,
         .defaultValue = vec3Json(d.origin), .help = "world position of the emitter (double; UTM coordinates are fine)",
         .valueName = "X,Y,Z", .count = 3, .editor = true},
        {.key = "start_s", .label = "Start", .unit = Unit::Seconds, .min = -1e6, .max = 1e6, .defaultValue = d.start,
         .help = "scene time emission starts (negative: already running at time 0)", .editor = true, .group = gWhen},
        {.key = "duration_s", .label = "Duration", .unit = Unit::Seconds, .min = 0.0, .max = 1e7,
         .defaultValue = d.duration, .help = "seconds of emission after the start", .editor = true, .group = gWhen},
        {.key = "rate_per_s", .label = "Rate", .unit = Unit::PerSecond, .min = 0.0, .max = 1e7, .defaultValue = d.rate,
         .help = "particles born per second when the rate is not keyed (also the range of every rate key)",
         .editor = true, .group = gWhen},
        {.key = "max_live", .label = "Live particles at most", .min = 1, .max = 1e8, .integer = true,
         .defaultValue = d.maxLive, .help = "cap on live particles; the oldest are kept and the rest counted as left out",
         .editor = true, .decimals = 0, .group = gWhen},
        {.key = "shape", .label = "Shape", .type = ParamType::Choice, .defaultValue = shapeName(d.shape),
         .choices = {kShapes, kShapes + 7}, .help = "where particles are born (terrain: on the ground inside the box's x, y extent)", .editor = true, .group = gWhen},
        {.key = "box_half_m", .label = "Box half extents", .unit = Unit::Metres, .min = 0.0, .max = 1e5,
         .defaultValue = vec3Json(d.boxHalf), .help = "box shape: half its size along x, y, z; terrain shape: the area's half size in x, y and the height above ground in z", .count = 3,
         .editor = true, .group = gWhen},
        {.key = "radius_m", .label = "Radius", .unit = Unit::Metres, .min = 0.0, .max = 1e5, .defaultValue = d.radius,
         .help = "sphere, disc and cone shapes: the radius", .editor = true, .group = gWhen},
        {.key = "surface_only", .label = "Surface only", .type = ParamType::Flag, .defaultValue = d.surfaceOnly,
         .help = "sphere: born on the surface; disc and cone: on the rim", .editor = true, .group = gWhen},
        {.key = "cone_angle_deg", .label = "Cone angle", .unit = Unit::Degrees, .min = 0.0, .max = 89.0,
         .defaultValue = d.coneAngleDeg, .help = "cone shape: half-angle of the opening", .editor = true,
         .group = gWhen},
        {.key = "mesh", .label = "Mesh", .type = ParamType::Text, .defaultValue = d.mesh,
         .help = "mesh shape: the entity whose mesh surface particles are born on", .editor = true, .group = gWhen},
        {.key = "space", .label = "Space", .type = ParamType::Choice, .defaultValue = spaceName(d.space),
         .choices = {kSpaces, kSpaces + 2},
         .help = "local: particles move with the emitter's entity; world: they stay where the emitter was at their "
                 "birth (a moving torch leaves its smoke behind)",
         .editor = true, .group = gWhen},
        {.key = "direction", .label = "Direction", .min = -1e3, .max = 1e3, .defaultValue = vec3Json(d.direction),
         .help = "initial direction (normalised; not zero)", .count = 3, .editor = true, .group = gStart},
        {.key = "spread_deg", .label = "Spread", .unit = Unit::Degrees, .min = 0.0, .max = 180.0,
         .defaultValue = d.spreadDeg, .help = "random deviation of the direction (a cone's half-angle)", .editor = true,
         .group = gStart},
        {.key = "along_normal", .label = "Along the normal", .type = ParamType::Flag, .defaultValue = d.alongNormal,
         .help = "start along the shape's normal (sphere: outwards) instead of the direction", .editor = true,
         .group = gStart},
        {.key = "speed_m_per_s", .label = "Speed", .unit = Unit::MetresPerSecond, .min = 0.0, .max = 1e4,
         .defaultValue = pairJson(d.speedMin, d.speedMax), .help = "initial speed, uniform in MIN,MAX",
         .valueName = "MIN,MAX", .count = 2, .editor = true, .group = gStart, .ordered = true},
        {.key = "lifetime_s", .label = "Lifetime", .unit = Unit::Seconds, .min = 0.0, .max = 1e4,
         .defaultValue = pairJson(d.lifetimeMin, d.lifetimeMax), .help = "life, uniform in MIN,MAX",
         .valueName = "MIN,MAX", .count = 2, .editor = true, .group = gStart, .ordered = true},
        {.key = "size_m", .label = "Size", .unit = Unit::Metres, .min = 0.0, .max = 1e4,
         .defaultValue = pairJson(d.sizeMin, d.sizeMax), .help = "sprite size at birth, uniform in MIN,MAX",
         .valueName = "MIN,MAX", .count = 2, .editor = true, .group = gStart, .ordered = true},
        {.key = "rotation_deg", .label = "Rotation", .unit = Unit::Degrees, .min = -360.0, .max = 360.0,
         .defaultValue = pairJson(d.rotationMinDeg, d.rotationMaxDeg), .help = "sprite rotation at birth",
         .valueName = "MIN,MAX", .count = 2, .editor = true, .group = gStart, .ordered = true},
        {.key = "spin_deg_per_s", .label = "Spin", .min = -1e5, .max = 1e5,
         .defaultValue = pairJson(d.spinMinDegPerS, d.spinMaxDegPerS), .help = "sprite spin, degrees per second",
         .valueName = "MIN,MAX", .count = 2, .editor = true, .group = gStart, .ordered = true},
        {.key = "gravity_m_per_s2", .label = "Gravity", .min = -1e3, .max = 1e3, .defaultValue = vec3Json(d.gravity),
         .help = "constant acceleration, m/s^2", .count = 3, .editor = true, .group = gForce},
        {.key = "drag_per_s", .label = "Drag", .unit = Unit::PerSecond, .min = 0.0, .max = 1e7,
         .defaultValue = d.drag, .help = "linear drag k: dv/dt = -k (v - wind) (integrated exactly, any k)",
         .editor = true, .group = gForce},
        {.key = "wind_m_per_s", .label = "Wind", .unit = Unit::MetresPerSecond, .min = -1e3, .max = 1e3,
         .defaultValue = vec3Json(d.wind), .help = "the air's velocity (acts through drag)", .count = 3,
         .editor = true, .group = gForce},
        {.key = "turbulence_m_per_s2", .label = "Turbulence", .min = 0.0, .max = 1e4, .defaultValue = d.turbulence,
         .help = "curl-noise acceleration's scale, m/s^2 (0: none; above 0 needs the replay)", .editor = true,
         .group = gForce},
        {.key = "turbulence_frequency_per_m", .label = "Turbulence frequency", .min = 0.0, .max = 1e3,
         .defaultValue = d.turbulenceFrequency, .help = "noise features per metre", .editor = true, .group = gForce},
        {.key = "turbulence_evolution_per_s", .label = "Turbulence evolution", .unit = Unit::PerSecond, .min = 0.0,
         .max = 1e3, .defaultValue = d.turbulenceEvolution, .help = "how fast the noise field changes",
         .editor = true, .group = gForce},
        {.key = "collision", .label = "Collision", .type = ParamType::Choice, .defaultValue = collisionName(d.collision),
         .choices = {kCollisions, kCollisions + 4}, .help = "what a particle does on hitting a collider",
         .editor = true, .group = gHit},
        {.key = "restitution", .label = "Restitution", .min = 0.0, .max = 1.0, .defaultValue = d.restitution,
         .help = "normal speed kept by a bounce (1: perfectly elastic)", .editor = true, .step = 0.05,
         .group = gHit},
        {.key = "friction", .label = "Friction", .min = 0.0, .max = 1.0, .defaultValue = d.friction,
         .help = "tangential speed lost by a bounce", .editor = true, .step = 0.05, .group = gHit},
        {.key = "rest_speed_m_per_s", .label = "Rest speed", .unit = Unit::MetresPerSecond, .min = 0.0, .max = 100.0,
         .defaultValue = d.restSpeed, .help = "a bounce leaving less normal speed than this comes to rest",
         .editor = true, .group = gHit},
        {.key = "replay_step_s", .label = "Replay step", .unit = Unit::Seconds, .min = 1e-4, .max = 1.0,
         .defaultValue = d.replayStep,
         .help = "fixed step of the turbulence and collision replay (the emitter's, never the frame rate's)",
         .editor = true, .decimals = 5, .step = 0.001, .group = gHit},
        {.key = "flipbook_frames", .label = "Flipbook frames", .min = 1, .max = 1024, .integer = true,
         .defaultValue = d.flipbookFrames, .help = "sprite frames played over a particle's life", .editor = true,
         .decimals = 0, .group = gLook},
        {.key = "sprite", .label = "Sprite", .type = ParamType::Choice, .defaultValue = spriteName(d.sprite),
         .choices = {kSprites, kSprites + 4}, .help = "the particle's picture (generated: snowflake, smoke puff, "
         "flame flipbook, round spark)", .editor = true, .group = gLook},
        {.key = "blend", .label = "Blend", .type = ParamType::Choice, .defaultValue = blendName(d.blend),
         .choices = {kBlends, kBlends + 2}, .help = "alpha: covers what is behind; additive: adds light (fire, sparks)",
         .editor = true, .group = gLook},
        {.key = "facing", .label = "Facing", .type = ParamType::Choice, .defaultValue = facingName(d.facing),
         .choices = {kFacings, kFacings + 2}, .help = "the quad faces the camera, or is stretched along the velocity",
         .editor = true, .group = gLook},
        {.key = "soft_m", .label = "Soft distance", .unit = Unit::Metres, .min = 0.0, .max = 1000.0,
         .defaultValue = d.softDistance, .help = "fades a particle over this distance in front of opaque surfaces (0: hard edges)",
         .editor = true, .step = 0.1, .group = gLook},
        {.key = "lit", .label = "Lit", .type = ParamType::Flag, .defaultValue = d.lit,
         .help = "lit by the sun and the sky (snow, fog, smoke); off: the colour is emitted light (fire)",
         .editor = true, .group = gLook},
        {.key = "draw_mesh", .label = "Draw mesh", .type = ParamType::Text, .defaultValue = d.drawMesh,
         .help = "draw each particle as this entity's mesh (its LODs and materials; its largest extent is the "
                 "particle's size); empty: the sprite",
         .editor = true, .group = gLook},
    };
  }();
  return decls;
}

// Declarations of the values inside the lists (not fields of their own).
const ParamDecl& keyTimeDecl() {
  static const ParamDecl d{.key = "t", .label = "Key time", .unit = Unit::Seconds, .min = -1e7, .max = 1e7,
                           .help = "scene time of a rate key or a burst"};
  return d;
}
const ParamDecl& burstCountDecl() {
  static const ParamDecl d{.key = "count", .label = "Burst count", .min = 0, .max = 1e7, .integer = true,
                           .help = "particles a burst makes"};
  return d;
}

namespace {

const ParamDecl& lifeFractionDecl() {
  static const ParamDecl d{.key = "x", .label = "Life fraction", .min = 0.0, .max = 1.0,
                           .help = "age / lifetime of an over-life key"};
  return d;
}
const ParamDecl& sizeMultiplierDecl() {
  static const ParamDecl d{.key = "size", .label = "Size multiplier", .min = 0.0, .max = 1e4,
                           .help = "size over life multiplies the size at birth"};
  return d;
}
const ParamDecl& colourDecl() {
  static const ParamDecl d{.key = "rgba", .label = "Colour", .min = 0.0, .max = 1e4,
                           .help = "linear RGB (HDR for fire) and opacity; opacity at most 1", .count = 4};
  return d;
}

template <class G, class S>
EmitterField bind(const char* key, G g, S s) {
  return EmitterField{&paramIn(emitterParamDecls(), key), g, s};
}

}  // namespace

const std::vector<EmitterField>& emitterFields() {
  using E = EmitterDesc;
  static const std::vector<EmitterField> fields = {
      bind("seed", [](const E& e) { return Json(e.seed); },
           [](E& e, const Json& v) { e.seed = uint32_t(v.get<double>()); }),
      bind("origin_m", [](const E& e) { return vec3Json(e.origin); }, [](E& e, const Json& v) { e.origin = jsonVec3(v); }),
      bind("start_s", [](const E& e) { return Json(e.start); }, [](E& e, const Json& v) { e.start = v.get<double>(); }),
      bind("duration_s", [](const E& e) { return Json(e.duration); },
           [](E& e, const Json& v) { e.duration = v.get<double>(); }),
      bind("rate_per_s", [](const E& e) { return Json(e.rate); }, [](E& e, const Json& v) { e.rate = v.get<double>(); }),
      bind("max_live", [](const E& e) { return Json(e.maxLive); },
           [](E& e, const Json& v) { e.maxLive = int64_t(v.get<double>()); }),
      bind("shape", [](const E& e) { return Json(shapeName(e.shape)); },
           [](E& e, const Json& v) { e.shape = enumFrom<Shape>(kShapes, v.get<std::string>()); }),
      bind("box_half_m", [](const E& e) { return vec3Json(e.boxHalf); },
           [](E& e, const Json& v) { e.boxHalf = jsonVec3(v); }),
      bind("radius_m", [](const E& e) { return Json(e.radius); }, [](E& e, const Json& v) { e.radius = v.get<double>(); }),
      bind("surface_only", [](const E& e) { return Json(e.surfaceOnly); },
           [](E& e, const Json& v) { e.surfaceOnly = v.get<bool>(); }),
      bind("cone_angle_deg", [](const E& e) { return Json(e.coneAngleDeg); },
           [](E& e, const Json& v) { e.coneAngleDeg = v.get<double>(); }),
      bind("mesh", [](const E& e) { return Json(e.mesh); }, [](E& e, const Json& v) { e.mesh = v.get<std::string>(); }),
      bind("space", [](const E& e) { return Json(spaceName(e.space)); },
           [](E& e, const Json& v) { e.space = enumFrom<Space>(kSpaces, v.get<std::string>()); }),
      bind("direction", [](const E& e) { return vec3Json(e.direction); },
           [](E& e, const Json& v) { e.direction = jsonVec3(v); }),
      bind("spread_deg", [](const E& e) { return Json(e.spreadDeg); },
           [](E& e, const Json& v) { e.spreadDeg = v.get<double>(); }),
      bind("along_normal", [](const E& e) { return Json(e.alongNormal); },
           [](E& e, const Json& v) { e.alongNormal = v.get<bool>(); }),
      bind("speed_m_per_s", [](const E& e) { return pairJson(e.speedMin, e.speedMax); },
           [](E& e, const Json& v) { e.speedMin = v[0].get<double>(), e.speedMax = v[1].get<double>(); }),
      bind("lifetime_s", [](const E& e) { return pairJson(e.lifetimeMin, e.lifetimeMax); },
           [](E& e, const Json& v) { e.lifetimeMin = v[0].get<double>(), e.lifetimeMax = v[1].get<double>(); }),
      bind("size_m", [](const E& e) { return pairJson(e.sizeMin, e.sizeMax); },
           [](E& e, const Json& v) { e.sizeMin = v[0].get<double>(), e.sizeMax = v[1].get<double>(); }),
      bind("rotation_deg", [](const E& e) { return pairJson(e.rotationMinDeg, e.rotationMaxDeg); },
           [](E& e, const Json& v) { e.rotationMinDeg = v[0].get<double>(), e.rotationMaxDeg = v[1].get<double>(); }),
      bind("spin_deg_per_s", [](const E& e) { return pairJson(e.spinMinDegPerS, e.spinMaxDegPerS); },
           [](E& e, const Json& v) { e.spinMinDegPerS = v[0].get<double>(), e.spinMaxDegPerS = v[1].get<double>(); }),
      bind("gravity_m_per_s2", [](const E& e) { return vec3Json(e.gravity); },
           [](E& e, const Json& v) { e.gravity = jsonVec3(v); }),
      bind("drag_per_s", [](const E& e) { return Json(e.drag); }, [](E& e, const Json& v) { e.drag = v.get<double>(); }),
      bind("wind_m_per_s", [](const E& e) { return vec3Json(e.wind); }, [](E& e, const Json& v) { e.wind = jsonVec3(v); }),
      bind("turbulence_m_per_s2", [](const E& e) { return Json(e.turbulence); },
           [](E& e, const Json& v) { e.turbulence = v.get<double>(); }),
      bind("turbulence_frequency_per_m", [](const E& e) { return Json(e.turbulenceFrequency); },
           [](E& e, const Json& v) { e.turbulenceFrequency = v.get<double>(); }),
      bind("turbulence_evolution_per_s", [](const E& e) { return Json(e.turbulenceEvolution); },
           [](E& e, const Json& v) { e.turbulenceEvolution = v.get<double>(); }),
      bind("collision", [](const E& e) { return Json(collisionName(e.collision)); },
           [](E& e, const Json& v) { e.collision = enumFrom<CollisionMode>(kCollisions, v.get<std::string>()); }),
      bind("restitution", [](const E& e) { return Json(e.restitution); },
           [](E& e, const Json& v) { e.restitution = v.get<double>(); }),
      bind("friction", [](const E& e) { return Json(e.friction); },
           [](E& e, const Json& v) { e.friction = v.get<double>(); }),
      bind("rest_speed_m_per_s", [](const E& e) { return Json(e.restSpeed); },
           [](E& e, const Json& v) { e.restSpeed = v.get<double>(); }),
      bind("replay_step_s", [](const E& e) { return Json(e.replayStep); },
           [](E& e, const Json& v) { e.replayStep = v.get<double>(); }),
      bind("flipbook_frames", [](const E& e) { return Json(e.flipbookFrames); },
           [](E& e, const Json& v) { e.flipbookFrames = int(v.get<double>()); }),
      bind("sprite", [](const E& e) { return Json(spriteName(e.sprite)); },
           [](E& e, const Json& v) { e.sprite = enumFrom<Sprite>(kSprites, v.get<std::string>()); }),
      bind("blend", [](const E& e) { return Json(blendName(e.blend)); },
           [](E& e, const Json& v) { e.blend = enumFrom<Blend>(kBlends, v.get<std::string>()); }),
      bind("facing", [](const E& e) { return Json(facingName(e.facing)); },
           [](E& e, const Json& v) { e.facing = enumFrom<Facing>(kFacings, v.get<std::string>()); }),
      bind("soft_m", [](const E& e) { return Json(e.softDistance); },
           [](E& e, const Json& v) { e.softDistance = v.get<double>(); }),
      bind("lit", [](const E& e) { return Json(e.lit); }, [](E& e, const Json& v) { e.lit = v.get<bool>(); }),
      bind("draw_mesh", [](const E& e) { return Json(e.drawMesh); },
           [](E& e, const Json& v) { e.drawMesh = v.get<std::string>(); }),
  };
  return fields;
}

const EmitterField* findEmitterField(std::string_view key) {
  for (const EmitterField& f : emitterFields())
    if (f.decl->key == key) return &f;
  return nullptr;
}

bool setEmitterField(EmitterDesc& e, std::string_view key, const Json& value, std::string& error) {
  const EmitterField* f = findEmitterField(key);
  if (!f) {
    error = "emitter '" + e.name + "': no field '" + std::string(key) + "'";
    return false;
  }
  std::string why;
  if (!checkParam(*f->decl, value, why)) {
    error = prefix(e, key) + why;
    return false;
  }
  f->set(e, value);
  return true;
}

namespace {

// Values of a list checked against the declaration they carry.
void checkNumber(const EmitterDesc& e, const std::string& where, const ParamDecl& d, double v,
                 std::vector<std::string>& out) {
  std::string why;
  if (!checkParam(d, Json(v), why)) out.push_back(prefix(e, where) + why);
}

template <class K>
void checkIncreasing(const EmitterDesc& e, const std::string& field, const std::vector<K>& keys,
                     std::vector<std::string>& out) {
  for (size_t i = 1; i < keys.size(); ++i) {
    if (!(keys[i].t > keys[i - 1].t)) {
      out.push_back(prefix(e, field + "[" + std::to_string(i) + "]") + "key time " + formatNumber(keys[i].t) +
                    (keys[i].t == keys[i - 1].t ? " coincides with the key before it"
                                                : " is before the key before it (" + formatNumber(keys[i - 1].t) + ")") +
                    "; keys must have strictly increasing times");
    }
  }
}

}  // namespace

std::vector<std::string> validate(const EmitterDesc& e) {
  std::vector<std::string> out;
  if (e.name.empty()) out.push_back("emitter '': the name is empty");
  for (const EmitterField& f : emitterFields()) {
    std::string why;
    if (!checkParam(*f.decl, f.get(e), why)) out.push_back(prefix(e, f.decl->key) + why);
  }
  const glm::dvec3 dir = e.direction;
  if (std::isfinite(dir.x + dir.y + dir.z) && dir.x * dir.x + dir.y * dir.y + dir.z * dir.z < 1e-24)
    out.push_back(prefix(e, "direction") + "the direction is zero; give a vector such as 0,0,1");
  if (e.shape == Shape::Mesh && e.mesh.empty())
    out.push_back(prefix(e, "mesh") + "the shape is 'mesh' but no mesh is named");
  for (size_t i = 0; i < e.rateKeys.keys.size(); ++i) {
    const std::string at = "rate_keys[" + std::to_string(i) + "]";
    checkNumber(e, at, keyTimeDecl(), e.rateKeys.keys[i].t, out);
    checkNumber(e, at, paramIn(emitterParamDecls(), "rate_per_s"), e.rateKeys.keys[i].value, out);
  }
  checkIncreasing(e, "rate_keys", e.rateKeys.keys, out);
  for (size_t i = 0; i < e.windKeys.size(); ++i) {
    const std::string at = "wind_keys[" + std::to_string(i) + "]";
    checkNumber(e, at, keyTimeDecl(), e.windKeys[i].t, out);
    std::string why;
    const glm::dvec3 w = e.windKeys[i].wind;
    if (!checkParam(paramIn(emitterParamDecls(), "wind_m_per_s"), Json::array({w.x, w.y, w.z}), why))
      out.push_back(prefix(e, at) + why);
  }
  checkIncreasing(e, "wind_keys", e.windKeys, out);
  for (size_t i = 0; i < e.bursts.size(); ++i) {
    const std::string at = "bursts[" + std::to_string(i) + "]";
    checkNumber(e, at, keyTimeDecl(), e.bursts[i].t, out);
    checkNumber(e, at, burstCountDecl(), double(e.bursts[i].count), out);
  }
  for (size_t i = 0; i < e.sizeOverLife.keys.size(); ++i) {
    const std::string at = "size_over_life[" + std::to_string(i) + "]";
    checkNumber(e, at, lifeFractionDecl(), e.sizeOverLife.keys[i].t, out);
    checkNumber(e, at, sizeMultiplierDecl(), e.sizeOverLife.keys[i].value, out);
  }
  checkIncreasing(e, "size_over_life", e.sizeOverLife.keys, out);
  for (size_t i = 0; i < e.colourOverLife.keys.size(); ++i) {
    const std::string at = "colour_over_life[" + std::to_string(i) + "]";
    const ColourKey& k = e.colourOverLife.keys[i];
    checkNumber(e, at, lifeFractionDecl(), k.t, out);
    std::string why;
    if (!checkParam(colourDecl(), Json::array({k.rgba.r, k.rgba.g, k.rgba.b, k.rgba.a}), why))
      out.push_back(prefix(e, at) + why);
    else if (k.rgba.a > 1.0)
      out.push_back(prefix(e, at) + "opacity " + formatNumber(k.rgba.a) + " is above 1");
  }
  checkIncreasing(e, "colour_over_life", e.colourOverLife.keys, out);
  return out;
}

Json emitterToJson(const EmitterDesc& e) {
  Json j = Json::object();
  j["name"] = e.name;
  for (const EmitterField& f : emitterFields()) j[f.decl->key] = f.get(e);
  Json rk = Json::array();
  for (const CurveKey& k : e.rateKeys.keys) rk.push_back(Json::array({k.t, k.value}));
  j["rate_keys"] = rk;
  Json b = Json::array();
  for (const Burst& x : e.bursts) b.push_back(Json::array({x.t, x.count}));
  j["bursts"] = b;
  Json wk = Json::array();
  for (const WindKey& k : e.windKeys) wk.push_back(Json::array({k.t, k.wind.x, k.wind.y, k.wind.z}));
  j["wind_keys"] = wk;
  Json s = Json::array();
  for (const CurveKey& k : e.sizeOverLife.keys) s.push_back(Json::array({k.t, k.value}));
  j["size_over_life"] = s;
  Json c = Json::array();
  for (const ColourKey& k : e.colourOverLife.keys) c.push_back(Json::array({k.t, k.rgba.r, k.rgba.g, k.rgba.b, k.rgba.a}));
  j["colour_over_life"] = c;
  return j;
}

namespace {

// Reads a list of fixed-size number rows ("[[t, v], ...]").
bool readRows(JsonReader& r, const Json& obj, const char* key, size_t n, const char* shape,
              std::vector<std::vector<double>>& rows) {
  const Json* list = r.required(obj, "", key);
  if (!list || !r.array(*list, key)) return false;
  for (size_t i = 0; i < list->size(); ++i) {
    std::vector<double> row(n);
    if (!r.numbers((*list)[i], jsonIndex(key, i), row.data(), n, shape)) return false;
    rows.push_back(std::move(row));
  }
  return true;
}

}  // namespace

std::optional<EmitterDesc> emitterFromJson(const Json& j, std::string& error, int formatVersion) {
  std::string err;
  JsonReader r(err);
  EmitterDesc e;
  e.name = "?";
  auto fail = [&](const std::string& what) {
    error = "emitter '" + e.name + "': " + what;
    return std::nullopt;
  };
  if (!r.object(j, "")) return fail(err);
  if (const Json* n = r.required(j, "", "name"); !n || !r.string(*n, "name", e.name)) return fail(err);
  std::set<std::string, std::less<>> known = {"name", "rate_keys", "bursts", "wind_keys", "size_over_life",
                                                "colour_over_life"};
  for (const EmitterField& f : emitterFields()) {
    known.insert(f.decl->key);
    if (emitterKeyAddedAfter(f.decl->key, formatVersion) && !JsonReader::member(j, f.decl->key)) continue;
    const Json* v = r.required(j, "", f.decl->key);
    if (!v) return fail(err);
    std::string why;
    if (!checkParam(*f.decl, *v, why)) {
      error = prefix(e, f.decl->key) + why + " (found " + jsonTypeName(*v) + " " + v->dump() + ")";
      return std::nullopt;
    }
    f.set(e, *v);
  }
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key())) return fail(it.key() + ": unknown field (a typo?)");
  std::vector<std::vector<double>> rows;
  if (!readRows(r, j, "rate_keys", 2, "[t, rate]", rows)) return fail(err);
  for (auto& x : rows) e.rateKeys.keys.push_back({x[0], x[1]});
  rows.clear();
  if (!readRows(r, j, "bursts", 2, "[t, count]", rows)) return fail(err);
  for (auto& x : rows) {
    if (x[1] != std::floor(x[1]) || x[1] < 0 || x[1] > 1e7)
      return fail("bursts: count " + formatNumber(x[1]) + " is not a whole number from 0 to 10000000");
    e.bursts.push_back({x[0], int64_t(x[1])});
  }
  rows.clear();
  if (!readRows(r, j, "wind_keys", 4, "[t, x, y, z]", rows)) return fail(err);
  for (auto& x : rows) e.windKeys.push_back({x[0], {x[1], x[2], x[3]}});
  rows.clear();
  if (!readRows(r, j, "size_over_life", 2, "[x, multiplier]", rows)) return fail(err);
  for (auto& x : rows) e.sizeOverLife.keys.push_back({x[0], x[1]});
  rows.clear();
  if (!readRows(r, j, "colour_over_life", 5, "[x, r, g, b, a]", rows)) return fail(err);
  for (auto& x : rows) e.colourOverLife.keys.push_back({x[0], {x[1], x[2], x[3], x[4]}});
  const glm::dvec3 d = e.direction;
  const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  if (len > 0.0) e.direction = d / len;
  const std::vector<std::string> problems = validate(e);
  if (!problems.empty()) {
    error = problems.front();
    return std::nullopt;
  }
  return e;
}

std::optional<EmitterDesc> emitterFromJsonText(std::string_view text, std::string& error) {
  const std::optional<Json> j = parseJson(text, error);
  if (!j) return std::nullopt;
  return emitterFromJson(*j, error);
}

}  // namespace hs::particles

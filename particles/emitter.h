#pragma once
// A particle emitter's description (docs/particles.md): where particles are
// born, how many and when, how they start, what moves them and what they
// look like over their life. A plain value: the scene stores it as JSON
// (emitterToJson / emitterFromJson), the evaluator (evaluate.h) turns it and
// a time into particles.
//
// Every scalar, tuple and choice is declared once in emitterParamDecls()
// (core/params.h): key, label, unit, range, default and help. The JSON
// reader and writer, validate(), the CLI's `set EMITTER particles.FIELD` and
// the editor's fields all use that one table (emitterFields()). Curves and
// bursts are lists; their values are checked against the declaration of the
// parameter they carry (rate keys against rate_per_s, and so on).
//
// Times are scene seconds. Positions: the emitter's origin is a world
// position in double (UTM-sized coordinates are fine); everything else is
// relative to it.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/json.h"
#include "core/params.h"
#include "particles/motion.h"

namespace hs::particles {

// Terrain: over the ground inside the box's x, y extent, from the ground up
// to the box's z half extent above it (the ground is given at evaluation).
enum class Shape { Point, Box, Sphere, Disc, Cone, Mesh, Terrain };
enum class CollisionMode { None, Bounce, Kill, Stick };
// How a particle is drawn (render/particle_source.h): its sprite (sprites.h:
// generated, no outside asset), how it blends (alpha: over what is behind,
// sorted with every other translucent surface; additive: light added, fire
// and sparks), and which way its quad faces (the camera, or stretched along
// its velocity for sparks and rain).
enum class Sprite { Snowflake, Smoke, Flame, Spark };
enum class Blend { Alpha, Additive };
enum class Facing { Camera, Velocity };
// Which frame particles live in once born (docs/particles.md, "Simulation
// space"): Local: the emitter's, so they move with an emitter whose entity
// moves (a lantern's glow); World: where the emitter was at their birth, so
// a moving torch leaves its smoke behind.
enum class Space { Local, World };

const char* shapeName(Shape s);
const char* collisionName(CollisionMode c);
const char* spriteName(Sprite s);
const char* blendName(Blend b);
const char* facingName(Facing f);
const char* spaceName(Space s);

// A piecewise-linear function of one variable: keys with strictly increasing
// t (coincident keys are refused by validate()), held constant before the
// first key and after the last. No keys: `fallback`.
struct CurveKey {
  double t = 0.0;
  double value = 0.0;
  bool operator==(const CurveKey&) const = default;
};
struct Curve {
  std::vector<CurveKey> keys{};
  double eval(double t, double fallback = 0.0) const;
  bool operator==(const Curve&) const = default;
};

// Colour (linear RGB) and opacity over a particle's life (t: age / lifetime).
struct ColourKey {
  double t = 0.0;
  glm::dvec4 rgba{1.0};
  bool operator==(const ColourKey&) const = default;
};
struct ColourCurve {
  std::vector<ColourKey> keys{};
  glm::dvec4 eval(double t) const;  // white, opaque with no keys
  bool operator==(const ColourCurve&) const = default;
};

// `count` particles born at once at scene time `t`.
struct Burst {
  double t = 0.0;
  int64_t count = 0;
  bool operator==(const Burst&) const = default;
};

struct EmitterDesc {
  std::string name = "Emitter";
  uint32_t seed = 1;

  // Where and when.
  glm::dvec3 origin{0.0};  // world position, metres (double)
  double start = 0.0;      // scene time emission starts (negative: already running at 0)
  double duration = 1e6;   // seconds of emission after start

  // How many: the rate (particles per second) over scene time, keyed,
  // piecewise linear; plus bursts. No rate keys: `rate`.
  double rate = 100.0;
  Curve rateKeys{};
  std::vector<Burst> bursts{};
  int64_t maxLive = 100000;  // cap on live particles (the oldest are kept)

  // Where particles are born, relative to the origin.
  Shape shape = Shape::Point;
  glm::dvec3 boxHalf{1.0, 1.0, 1.0};  // Box: half extents; Terrain: x, y half extents and the height above ground
  double radius = 1.0;                // Sphere, Disc, Cone (base)
  bool surfaceOnly = false;           // Sphere/Disc: on the surface/rim only
  double coneAngleDeg = 25.0;         // Cone: half-angle of the opening
  std::string mesh{};                 // Mesh: the surface's entity name (a SurfaceSampler is given at evaluation)
  Space space = Space::Local;         // the frame particles live in after their birth

  // How they start.
  glm::dvec3 direction{0.0, 0.0, 1.0};  // unit vector (normalised when read)
  double spreadDeg = 0.0;               // random deviation of the direction: half-angle of a cone
  bool alongNormal = false;             // start along the shape's normal (sphere: outwards) instead of `direction`
  double speedMin = 1.0, speedMax = 1.0;
  double lifetimeMin = 2.0, lifetimeMax = 2.0;
  double sizeMin = 0.1, sizeMax = 0.1;  // metres
  double rotationMinDeg = 0.0, rotationMaxDeg = 0.0;
  double spinMinDegPerS = 0.0, spinMaxDegPerS = 0.0;

  // What moves them: dv/dt = gravity + turbulence - drag (v - wind).
  glm::dvec3 gravity{0.0, 0.0, -9.81};  // m/s^2
  double drag = 0.0;                    // k, per second
  glm::dvec3 wind{0.0};                 // m/s, the air's velocity
  std::vector<WindKey> windKeys{};      // keyed wind over scene time (piecewise linear); none: `wind`
  double turbulence = 0.0;              // m/s^2, curl-noise acceleration's scale
  double turbulenceFrequency = 0.2;     // per metre
  double turbulenceEvolution = 0.1;     // per second: how fast the noise field changes

  // What stops them.
  CollisionMode collision = CollisionMode::None;
  double restitution = 0.5;  // normal speed kept by a bounce (0..1)
  double friction = 0.0;     // tangential speed lost by a bounce (0..1)
  double restSpeed = 0.05;   // a bounce leaving less normal speed than this comes to rest

  // The fixed step of the replay that turbulence and collision need
  // (evaluate.h): a property of the emitter, never of the frame rate.
  double replayStep = 1.0 / 120.0;

  // What they look like over life (x: age / lifetime in [0, 1]).
  Curve sizeOverLife{};      // multiplies the size; no keys: 1
  ColourCurve colourOverLife{};  // no keys: white, opaque
  int flipbookFrames = 1;    // sprite frames played over the life
  Sprite sprite = Sprite::Smoke;
  Blend blend = Blend::Alpha;
  Facing facing = Facing::Camera;
  double softDistance = 0.5;  // metres over which a particle fades in front of opaque geometry (0: hard)
  bool lit = true;            // lit by the sun (with its shadows) and the sky; false: its colour is emitted light
  // Non-empty: each particle is drawn as this entity's mesh (its LOD chain
  // and materials), scaled so its largest extent is the particle's size,
  // turned by its rotation about an axis of its own; empty: a sprite.
  std::string drawMesh{};

  bool operator==(const EmitterDesc&) const = default;

  // Particles per second at scene time t (0 outside [start, start + duration]).
  double rateAt(double t) const;
  // Whether particles need the fixed-step replay (turbulence or collision).
  bool needsReplay() const { return turbulence > 0.0 || collision != CollisionMode::None; }
};

// The declared parameters (core/params.h): one per scalar, tuple or choice
// field of EmitterDesc, in the order files and reports list them. Keys:
// seed origin_m start_s duration_s rate_per_s max_live shape box_half_m
// radius_m surface_only cone_angle_deg mesh direction spread_deg
// along_normal speed_m_per_s lifetime_s size_m rotation_deg spin_deg_per_s
// gravity_m_per_s2 drag_per_s wind_m_per_s turbulence_m_per_s2
// turbulence_frequency_per_m turbulence_evolution_per_s collision
// restitution friction rest_speed_m_per_s replay_step_s flipbook_frames
// sprite blend facing soft_m lit, and since format 11 (emitterKeyAddedAfter)
// space draw_mesh.
const std::vector<ParamDecl>& emitterParamDecls();
// The values inside the keyed lists: a key's scene time (rate_keys,
// wind_keys, bursts) and a burst's count.
const ParamDecl& keyTimeDecl();
const ParamDecl& burstCountDecl();

// A declared parameter bound to its EmitterDesc member: the one table the
// JSON reader/writer, validate() and the CLI's `set` go through.
struct EmitterField {
  const ParamDecl* decl = nullptr;
  std::function<Json(const EmitterDesc&)> get;
  std::function<void(EmitterDesc&, const Json&)> set;  // the value has passed checkParam
};
const std::vector<EmitterField>& emitterFields();
const EmitterField* findEmitterField(std::string_view key);

// Sets one field from a JSON value (a number, a tuple as an array, a choice
// as a string), checked by its declaration. false with `error` naming the
// emitter and the field ("emitter 'Snow', field 'drag_per_s': Drag: -1 is
// out of range (0 to 10000000 per second)").
bool setEmitterField(EmitterDesc& e, std::string_view key, const Json& value, std::string& error);

// Every problem of `e`, each naming the emitter and the field: values out
// of their declared ranges or not finite, min above max, a zero direction,
// curves with keys not strictly increasing (coincident keys) or out of
// [0, 1] for over-life curves, wind keys out of the wind's range, negative or NaN rates and burst counts, a
// mesh shape without a mesh name. Empty: valid.
// (The mesh shape's surface and draw_mesh name entities; whether they exist
// is the scene's to say, at evaluation and drawing.)
std::vector<std::string> validate(const EmitterDesc& e);

// JSON (core/json.h): an object with "name", every declared key, and the
// lists "rate_keys" [[t, rate], ...], "bursts" [[t, count], ...],
// "wind_keys" [[t, x, y, z], ...], "size_over_life" [[x, multiplier], ...], "colour_over_life" [[x, r, g, b,
// a], ...]. emitterFromJson is strict: every key must be there with the
// right type and a finite value in range, and unknown keys are refused
// (a typo is not silently ignored); the error names the emitter, the JSON
// path and what was wrong, and validate() runs on the result.
// `formatVersion`: the scene file's; keys added after it (an emitter
// written by format 10 has no "space" or "draw_mesh") take their defaults.
inline constexpr int kEmitterFormatLatest = 11;
bool emitterKeyAddedAfter(std::string_view key, int formatVersion);
Json emitterToJson(const EmitterDesc& e);
std::optional<EmitterDesc> emitterFromJson(const Json& j, std::string& error, int formatVersion = kEmitterFormatLatest);
// From text: parse errors with line and column, field errors placed in the text.
std::optional<EmitterDesc> emitterFromJsonText(std::string_view text, std::string& error);

}  // namespace hs::particles

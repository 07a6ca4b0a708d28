#include "scene/demo_particles.h"

#include "foliage/surface.h"
#include "scene/document.h"
#include "scene/operations.h"
#include "scene/foliage_ground.h"
#include "scene/particle_ops.h"
#include "scene/sequence_edits.h"

namespace hs::scene {
namespace {

// Through the same operation as `particles add` (one place decides how a
// preset becomes entities), on a document holding the demo for a moment.
bool addPreset(Document& doc, const char* preset, const particles::PresetOptions& o, bool atGiven, std::string& error) {
  if (ops::addParticles(doc, preset, o, atGiven, error) != kNoEntity) return true;
  error = std::string("demo particles: ") + preset + ": " + error;
  return false;
}

// The ground's height at a world XY (0 off the terrain).
double groundAt(const SceneState& s, double x, double y) {
  const FoliageGround ground(s, false);
  if (const terrain::Terrain* t = ground.ground().terrain)
    if (auto p = foliage::terrainSurface(t->height, {x, y})) return p->position.z;
  return 0.0;
}

bool setValue(Document& doc, EntityId id, const char* key, const Json& v, std::string& error) {
  if (ops::setEmitterValue(doc, id, key, v, error)) return true;
  error = "demo particles: " + error;
  return false;
}

bool addDemoEmitters(Document& doc, std::string& error) {
  // Snow around the clearing, where the first camera looks: 60 x 60 m, 400
  // flakes a second of 3 to 6 cm (larger than the preset's, to be seen at
  // a preview's size), born 12 m above the ground, falling for about ten
  // seconds and sticking where they land: about 5,000 in the air. Each
  // flake is replayed for its turbulence and collision (docs/particles.md,
  // "The replay"): a cold frame (a farm node's first) costs a few hundred
  // milliseconds on two cores, a warm one milliseconds.
  const double snowZ = groundAt(doc.state(), 0.0, 5.0) + 12.0 - 30.0;  // the preset adds 30 m
  particles::PresetOptions snow{.at = {0.0, 5.0, snowZ}, .area = glm::dvec4(-30.0, -25.0, 30.0, 35.0), .rate = 400.0,
                                .seed = 7};
  if (!addPreset(doc, "snow", snow, true, error)) return false;
  const EntityId flakes = doc.state().findByName("Snow");
  if (!setValue(doc, flakes, "lifetime_s", Json::array({11.0, 13.0}), error) ||
      !setValue(doc, flakes, "size_m", Json::array({0.03, 0.06}), error))
    return false;
  // The snow thickens over the shot: the flakes' size keyed on the timeline
  // (docs/particles.md, "On the timeline"), from the field's own centre at
  // 0 s (so the first frame is the unkeyed one) to twice it at 20 s, each
  // flake keeping the size it was born with.
  const std::optional<AnimTarget> size = animationTarget("particles.size_m", error);
  if (!size ||
      !ops::setKeys(doc, {{flakes, *size, sequencer::PropertyValue(0.045)}}, 0.0, std::nullopt, "Key", {}, &error) ||
      !ops::setKeys(doc, {{flakes, *size, sequencer::PropertyValue(0.09)}}, 20.0, std::nullopt, "Key", {}, &error)) {
    error = "demo particles: keying the snow's size: " + error;
    return false;
  }
  // A fog bank on the valley floor in front of and between the pillars.
  particles::PresetOptions fog{.area = glm::dvec4(-90.0, 60.0, 90.0, 150.0), .seed = 3};
  if (!addPreset(doc, "fog", fog, false, error)) return false;
  // A torch on the tallest pillar's top (-12, 140), 1.2 m above its rock.
  const glm::dvec3 top(-12.0, 140.0, groundAt(doc.state(), -12.0, 140.0) + 1.2);
  particles::PresetOptions torch{.name = "Monastery torch", .at = top, .seed = 5};
  if (!addPreset(doc, "torch", torch, true, error)) return false;
  // Dust kicked up behind the running bunny: a world-space emitter under
  // the keyed instance, so the puffs stay where they were born and trail
  // behind it (docs/particles.md, "Simulation space").
  const EntityId runner = doc.state().findByName("Bunny (instance)");
  if (runner != kNoEntity) {
    const glm::dvec3 at = glm::dvec3(doc.state().worldMatrix(runner)[3]);
    particles::PresetOptions dust{.name = "Bunny dust", .at = at, .area = glm::dvec4(at.x - 0.4, at.y - 0.4, at.x + 0.4, at.y + 0.4),
                                  .rate = 25.0, .seed = 13};
    if (!addPreset(doc, "dust", dust, true, error)) return false;
    const EntityId trail = doc.state().findByName("Bunny dust");
    if (!ops::reparent(doc, trail, runner) || !setValue(doc, trail, "space", "world", error) ||
        !setValue(doc, trail, "size_m", Json::array({0.3, 0.8}), error) ||
        !setValue(doc, trail, "lifetime_s", Json::array({2.0, 4.0}), error))
      return false;
  }
  // Rocks falling from the pillar's rim, bouncing down to the valley floor:
  // mesh particles (draw_mesh) drawing the hidden "Rockfall stone", the
  // demo's boulder, scaled to each particle's size, colliding with the terrain.
  const EntityId rockfall = ops::addParticles(doc, "dust", {.name = "Rockfall", .at = top, .rate = 2.0, .seed = 17},
                                             true, error);
  if (rockfall == kNoEntity) {
    error = "demo particles: Rockfall: " + error;
    return false;
  }
  const glm::dvec3 rim = top + glm::dvec3(6.0, -6.0, -1.0);
  return setValue(doc, rockfall, "origin_m", Json::array({rim.x, rim.y, rim.z}), error) &&
         setValue(doc, rockfall, "box_half_m", Json::array({2.0, 2.0, 0.2}), error) &&
         setValue(doc, rockfall, "speed_m_per_s", Json::array({1.0, 3.0}), error) &&
         setValue(doc, rockfall, "spread_deg", 40.0, error) &&
         setValue(doc, rockfall, "lifetime_s", Json::array({8.0, 10.0}), error) &&
         setValue(doc, rockfall, "size_m", Json::array({0.3, 0.7}), error) &&
         setValue(doc, rockfall, "drag_per_s", 0.0, error) &&
         setValue(doc, rockfall, "wind_m_per_s", Json::array({0.0, 0.0, 0.0}), error) &&
         setValue(doc, rockfall, "turbulence_m_per_s2", 0.0, error) &&
         setValue(doc, rockfall, "gravity_m_per_s2", Json::array({0.0, 0.0, -9.81}), error) &&
         setValue(doc, rockfall, "collision", "bounce", error) &&
         setValue(doc, rockfall, "restitution", 0.35, error) && setValue(doc, rockfall, "friction", 0.5, error) &&
         setValue(doc, rockfall, "draw_mesh", "Rockfall stone", error);
}

}  // namespace

bool addDemoParticles(SceneState& s, std::string& error) {
  // The rockfall's stone: the demo's boulder, hidden (drawn only as the
  // emitter's particles).
  for (const auto& [id, a] : s.assets)
    if (a.name == "Boulder") {
      Entity stone;
      stone.id = s.maxEntityId() + 1;
      stone.name = "Rockfall stone";
      stone.mesh = MeshInstance{id};
      stone.visible = false;
      s.entities.emplace(stone.id, stone);
      s.roots.push_back(stone.id);
      break;
    }
  Document doc;
  doc.reset(std::move(s), QString());
  const bool ok = addDemoEmitters(doc, error);
  s = doc.state();
  return ok;
}

}  // namespace hs::scene

#include "scene/demo_particles.h"

#include "foliage/surface.h"
#include "scene/foliage_ground.h"
#include "scene/particle_ops.h"

namespace hs::scene {
namespace {

void addPlaced(SceneState& s, ops::PlacedPreset placed) {
  EntityId parent = kNoEntity;
  auto add = [&s](Entity e, EntityId p) {
    e.id = s.maxEntityId() + 1;
    e.parent = p;
    if (p == kNoEntity)
      s.roots.push_back(e.id);
    else
      s.entities[p].children.push_back(e.id);
    const EntityId id = e.id;
    s.entities.emplace(id, std::move(e));
    return id;
  };
  if (placed.group) parent = add(std::move(*placed.group), kNoEntity);
  for (Entity& e : placed.emitters) add(std::move(e), parent);
}

bool addPreset(SceneState& s, const char* preset, const particles::PresetOptions& o, bool atGiven, std::string& error) {
  std::optional<ops::PlacedPreset> placed = ops::placePreset(s, preset, o, atGiven, error);
  if (!placed) {
    error = std::string("demo particles: ") + preset + ": " + error;
    return false;
  }
  addPlaced(s, std::move(*placed));
  return true;
}

}  // namespace

bool addDemoParticles(SceneState& s, std::string& error) {
  // Light snow over 160 x 160 m around the clearing: 200 flakes a second,
  // about 7,000 in the air, born 30 m above the ground at the area's centre,
  // sticking where they land. Each flake is replayed for its turbulence and
  // collision (docs/particles.md, "The replay"): a cold frame (a farm node's
  // first) costs about a second on two cores, a warm one milliseconds.
  particles::PresetOptions snow{.area = glm::dvec4(-80.0, -40.0, 80.0, 120.0), .rate = 200.0, .seed = 7};
  if (!addPreset(s, "snow", snow, false, error)) return false;
  // A fog bank in the gap between the first pillars and the tallest one.
  particles::PresetOptions fog{.area = glm::dvec4(-70.0, 85.0, 60.0, 150.0), .seed = 3};
  if (!addPreset(s, "fog", fog, false, error)) return false;
  // A torch on the tallest pillar's top (-12, 140), 1.2 m above its rock.
  glm::dvec3 top(-12.0, 140.0, 0.0);
  {
    const FoliageGround ground(s, false);
    if (const terrain::Terrain* t = ground.ground().terrain)
      if (auto p = foliage::terrainSurface(t->height, {top.x, top.y})) top.z = p->position.z;
  }
  particles::PresetOptions torch{.name = "Monastery torch", .at = top + glm::dvec3(0.0, 0.0, 1.2), .seed = 5};
  return addPreset(s, "torch", torch, true, error);
}

}  // namespace hs::scene

#include "scene/demo_particles.h"

#include "foliage/surface.h"
#include "scene/document.h"
#include "scene/foliage_ground.h"
#include "scene/particle_ops.h"

namespace hs::scene {
namespace {

// Through the same operation as `particles add` (one place decides how a
// preset becomes entities), on a document holding the demo for a moment.
bool addPreset(Document& doc, const char* preset, const particles::PresetOptions& o, bool atGiven, std::string& error) {
  if (ops::addParticles(doc, preset, o, atGiven, error) != kNoEntity) return true;
  error = std::string("demo particles: ") + preset + ": " + error;
  return false;
}

bool addDemoEmitters(Document& doc, std::string& error) {
  // Light snow over 160 x 160 m around the clearing: 200 flakes a second,
  // about 7,000 in the air, born 30 m above the ground at the area's centre,
  // sticking where they land. Each flake is replayed for its turbulence and
  // collision (docs/particles.md, "The replay"): a cold frame (a farm node's
  // first) costs about a second on two cores, a warm one milliseconds.
  particles::PresetOptions snow{.area = glm::dvec4(-80.0, -40.0, 80.0, 120.0), .rate = 200.0, .seed = 7};
  if (!addPreset(doc, "snow", snow, false, error)) return false;
  // A fog bank in the gap between the first pillars and the tallest one.
  particles::PresetOptions fog{.area = glm::dvec4(-70.0, 85.0, 60.0, 150.0), .seed = 3};
  if (!addPreset(doc, "fog", fog, false, error)) return false;
  // A torch on the tallest pillar's top (-12, 140), 1.2 m above its rock.
  glm::dvec3 top(-12.0, 140.0, 0.0);
  {
    const FoliageGround ground(doc.state(), false);
    if (const terrain::Terrain* t = ground.ground().terrain)
      if (auto p = foliage::terrainSurface(t->height, {top.x, top.y})) top.z = p->position.z;
  }
  particles::PresetOptions torch{.name = "Monastery torch", .at = top + glm::dvec3(0.0, 0.0, 1.2), .seed = 5};
  return addPreset(doc, "torch", torch, true, error);
}

}  // namespace

bool addDemoParticles(SceneState& s, std::string& error) {
  Document doc;
  doc.reset(std::move(s), QString());
  const bool ok = addDemoEmitters(doc, error);
  s = doc.state();
  return ok;
}

}  // namespace hs::scene

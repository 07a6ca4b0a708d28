#include "scene/demo_particles.h"

#include "foliage/surface.h"
#include "scene/document.h"
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

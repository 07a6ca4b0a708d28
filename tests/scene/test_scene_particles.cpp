// Particle emitters in the document (docs/particles.md, "In the document"):
// presets as entities through the command API (one undo step, parent and
// children for several emitters, origins where asked), every field set
// checked as a file's emitter is (a refused value names emitter and field
// and leaves the document as it was), the .hscene round trip, a damaged
// emitter refusing the file with its path, the scene's colliders (snow
// sticks on the terrain within 1 mm of the terrain's own surface), a mesh
// shape born on its entity's surface, UTM-sized positions, and the live
// counts `info --time` prints against the evaluator's own frame.
#include <QtTest>

#include <cmath>
#include <filesystem>
#include <map>

#include <sqlite3.h>

#include "foliage/surface.h"
#include "particles/evaluate.h"
#include "scene/animation.h"
#include "scene/camera_path_edits.h"
#include "scene/demo_scene.h"
#include "scene/edit.h"
#include "sequencer/camera_path_edit.h"
#include "sequencer/track.h"
#include "scene/document.h"
#include "scene/foliage_ground.h"
#include "scene/hscene_file.h"
#include "scene/operations.h"
#include "scene/particle_ops.h"
#include "scene/particle_world.h"
#include "scene/scene_json.h"
#include "scene/sequence_edits.h"
#include "scene/terrain_ops.h"

using namespace hs;
using namespace hs::scene;

namespace {

EntityId makeTerrain(Document& doc) {
  ops::NewTerrain spec;
  spec.name = "Valley";
  spec.samplesX = spec.samplesY = 65;
  spec.sizeMetres = glm::dvec2(128.0);
  spec.start = ops::NewTerrain::Start::Hills;
  spec.heightRange = {0.0f, 20.0f};
  std::string error;
  const EntityId id = ops::addTerrain(doc, spec, error);
  if (id == kNoEntity) qFatal("addTerrain: %s", error.c_str());
  return id;
}

EntityId addPreset(Document& doc, const char* preset, particles::PresetOptions o, bool atGiven = true) {
  std::string error;
  const EntityId id = ops::addParticles(doc, preset, o, atGiven, error);
  if (id == kNoEntity) qFatal("addParticles %s: %s", preset, error.c_str());
  return id;
}

// A small emitter: a point, a few particles a second, closed form only.
particles::EmitterDesc small(double rate = 20.0) {
  particles::EmitterDesc d;
  d.rate = rate;
  d.lifetimeMin = d.lifetimeMax = 2.0;
  d.speedMin = d.speedMax = 1.0;
  d.start = 0.0;
  return d;
}

// An entity with `d` as its emitter, through the command API (three steps).
EntityId addEmitter(Document& doc, const std::string& name, const glm::dvec3& at, const particles::EmitterDesc& d) {
  Transform t;
  t.translation = at;
  const EntityId id = ops::addEmpty(doc, name, t);
  std::string error;
  if (!ops::addComponent(doc, id, *findComponent("particles")) || !ops::setEmitter(doc, id, d, error))
    qFatal("addEmitter: %s", error.c_str());
  return id;
}

// A linear translation track on `id` from `a` at 0 s to `b` at 4 s.
void moveLinearly(Document& doc, EntityId id, const glm::dvec3& a, const glm::dvec3& b) {
  Edit e(doc, "Move");
  sequencer::Binding binding;
  binding.entity = id;
  sequencer::VectorTrack move;
  move.property = "transform.translation";
  sequencer::VectorKey k0, k1;
  k0.time = 0.0, k0.value = a, k0.interpolation = sequencer::Interpolation::Linear;
  k1.time = 4.0, k1.value = b, k1.interpolation = sequencer::Interpolation::Linear;
  move.keys = {k0, k1};
  binding.tracks.push_back(move);
  e.sequence().bindings.push_back(binding);
  e.commit();
}

// World position of the entity at t, by the scene's own animation (the
// reference EmitterMotion must agree with).
glm::dvec3 animatedWorld(const SceneState& s, EntityId id, double t) {
  const SceneState at = animatedState(s, compileSequence(s), t);
  return glm::dvec3(at.worldMatrix(id)[3]);
}

std::string tempPath(const char* name) {
  static QTemporaryDir dir;
  return dir.filePath(name).toStdString();
}

}  // namespace

class TestSceneParticles : public QObject {
  Q_OBJECT

 private slots:
  void presetsBecomeEntitiesInOneUndoStep() {
    Document doc;
    const int before = doc.undoStack()->count();
    const glm::dvec3 at(120.0, 310.0, 412.0);
    const EntityId torch = addPreset(doc, "torch", {.name = "Gate torch", .at = at});
    std::string error;
    const std::vector<particles::EmitterDesc> made = particles::makePreset("torch", {.name = "Gate torch", .at = at}, error);
    QCOMPARE(doc.undoStack()->count(), before + 1);
    const Entity group = *doc.state().find(torch);  // a copy: undo below removes it
    QCOMPARE(group.name, std::string("Gate torch"));
    QVERIFY(!group.particles);
    QCOMPARE(group.children.size(), size_t(2));  // flame and smoke
    for (size_t i = 0; i < group.children.size(); ++i) {
      const EntityId c = group.children[i];
      const auto d = emitterInWorld(doc.state(), c);
      QVERIFY(d);
      QVERIFY2(glm::length(d->origin - made[i].origin) < 1e-9, "each emitter sits where the preset put it");
      QCOMPARE(d->name, doc.state().find(c)->name);
      QVERIFY(particles::validate(*d).empty());
    }
    QCOMPARE(doc.state().find(group.children[0])->name, std::string("Gate torch flame"));
    QCOMPARE(emitterInWorld(doc.state(), group.children[0])->origin, at);  // the flame at the torch itself
    // One emitter: one entity, named after the preset; a second gets " 2".
    const EntityId snow = addPreset(doc, "snow", {.area = glm::dvec4(-10, -10, 10, 10)}, false);
    QCOMPARE(doc.state().find(snow)->name, std::string("Snow"));
    QVERIFY(doc.state().find(snow)->particles);
    const EntityId snow2 = addPreset(doc, "snow", {});
    QCOMPARE(doc.state().find(snow2)->name, std::string("Snow 2"));
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    QVERIFY(!doc.state().find(torch));
    for (EntityId c : group.children) QVERIFY(!doc.state().find(c));
    doc.undoStack()->redo();
    QVERIFY(doc.state().find(torch) && doc.state().find(torch)->children.size() == 2);
  }

  void unknownPresetListsTheNames() {
    Document doc;
    std::string error;
    QCOMPARE(ops::addParticles(doc, "rain", {}, true, error), kNoEntity);
    for (const char* n : {"rain", "snow", "fog", "torch", "campfire", "dust"})
      QVERIFY2(error.find(n) != std::string::npos, error.c_str());
    QCOMPARE(doc.undoStack()->count(), 0);
  }

  void areaPresetsStandOnTheGround() {
    Document doc;
    makeTerrain(doc);
    const EntityId fog = addPreset(doc, "fog", {.area = glm::dvec4(-20, -30, 40, 10)}, false);
    const FoliageGround ground(doc.state(), false);
    const auto surface = foliage::terrainSurface(ground.ground().terrain->height, {10.0, -10.0});
    QVERIFY(surface);
    const auto d = emitterInWorld(doc.state(), fog);
    QCOMPARE(d->origin.x, 10.0);
    QCOMPARE(d->origin.y, -10.0);
    // The fog bank's box sits 3 m above the ground at the area's centre.
    QVERIFY2(std::abs(d->origin.z - (surface->position.z + 3.0)) < 1e-9, std::to_string(d->origin.z).c_str());
  }

  void refusedValuesNameEmitterAndFieldAndChangeNothing() {
    Document doc;
    const EntityId id = addPreset(doc, "dust", {.name = "Road dust"});
    const SceneState before = doc.state();
    const int steps = doc.undoStack()->count();
    struct Case {
      const char* key;
      Json value;
      const char* says;
    };
    const Case cases[] = {
        {"drag_per_s", std::nan(""), "drag_per_s"},
        {"drag_per_s", -1.0, "drag_per_s"},
        {"rate_per_s", -5.0, "rate_per_s"},
        {"lifetime_s", Json::array({5.0, 1.0}), "lifetime_s"},
        {"size_m", Json::array({std::nan(""), 1.0}), "size_m"},
        {"rate_keys", Json::parse("[[1, 10], [1, 20]]"), "rate_keys"},
        {"colour_over_life", Json::parse("[[0, 1, 1, 1]]"), "colour_over_life"},
        {"shape", "blob", "shape"},
        {"no_such_field", 1.0, "no_such_field"},
    };
    for (const Case& c : cases) {
      std::string error;
      QVERIFY2(!ops::setEmitterValue(doc, id, c.key, c.value, error), c.key);
      QVERIFY2(error.find(c.says) != std::string::npos, error.c_str());
      if (std::string(c.key) != "no_such_field")
        QVERIFY2(error.find("Road dust") != std::string::npos, error.c_str());
    }
    QCOMPARE(doc.undoStack()->count(), steps);
    QVERIFY(doc.state().find(id)->particles->desc == before.find(id)->particles->desc);
    // A good value is one undo step; Undo gives the old one back.
    std::string error;
    bool changed = false;
    QVERIFY2(ops::setEmitterValue(doc, id, "rate_keys", Json::parse("[[0, 10], [5, 400]]"), error, {}, &changed),
             error.c_str());
    QVERIFY(changed);
    QCOMPARE(doc.undoStack()->count(), steps + 1);
    QCOMPARE(doc.state().find(id)->particles->desc.rateAt(2.5), 10.0 + 0.5 * 390.0);
    doc.undoStack()->undo();
    QVERIFY(doc.state().find(id)->particles->desc == before.find(id)->particles->desc);
    // Text as `set` takes it.
    auto v = ops::parseEmitterValue("Road dust", "speed_m_per_s", "0.5,2", error);
    QVERIFY2(v, error.c_str());
    QVERIFY(ops::setEmitterValue(doc, id, "speed_m_per_s", *v, error));
    QCOMPARE(doc.state().find(id)->particles->desc.speedMax, 2.0);
    QVERIFY(!ops::parseEmitterValue("Road dust", "bursts", "[[0, 5]", error));
    QVERIFY2(error.find("bursts") != std::string::npos, error.c_str());
  }

  // Keying the rate and the wind at a time (the panel's Key at Playhead,
  // `key EMITTER particles.rate_per_s`): a row of the emitter's own list,
  // in time order, one at a time replaced, each one undo step; refused
  // values and fields named, nothing changed.
  void rateAndWindKeyedIntoTheirLists() {
    Document doc;
    const EntityId id = addPreset(doc, "dust", {.name = "Road dust"});
    const int steps = doc.undoStack()->count();
    std::string error;
    QVERIFY2(ops::keyEmitterField(doc, id, "rate_per_s", 5.0, 400.0, error), error.c_str());
    QVERIFY2(ops::keyEmitterField(doc, id, "rate_per_s", 1.0, 10.0, error), error.c_str());
    QVERIFY2(ops::keyEmitterField(doc, id, "rate_per_s", 3.0, 50.0, error), error.c_str());
    bool changed = true;
    QVERIFY2(ops::keyEmitterField(doc, id, "rate_per_s", 3.0, 80.0, error, &changed), error.c_str());  // replaces
    QVERIFY(changed);
    QCOMPARE(doc.undoStack()->count(), steps + 4);
    const particles::EmitterDesc* d = &doc.state().find(id)->particles->desc;
    QCOMPARE(d->rateKeys.keys.size(), size_t(3));
    QCOMPARE(d->rateKeys.keys[0].t, 1.0);
    QCOMPARE(d->rateKeys.keys[1].value, 80.0);
    QCOMPARE(d->rateKeys.keys[2].t, 5.0);
    QCOMPARE(d->rateAt(4.0), 80.0 + 0.5 * 320.0);
    QVERIFY(ops::keyEmitterField(doc, id, "rate_per_s", 3.0, 80.0, error, &changed));  // the same key again
    QVERIFY(!changed);
    QCOMPARE(doc.undoStack()->count(), steps + 4);
    QVERIFY2(ops::keyEmitterField(doc, id, "wind_m_per_s", 2.0, Json::array({1.0, 0.0, 0.5}), error), error.c_str());
    d = &doc.state().find(id)->particles->desc;
    QCOMPARE(d->windKeys.size(), size_t(1));
    QCOMPARE(d->windKeys[0].wind, glm::dvec3(1.0, 0.0, 0.5));
    doc.undoStack()->undo();
    QVERIFY(doc.state().find(id)->particles->desc.windKeys.empty());

    const particles::EmitterDesc before = doc.state().find(id)->particles->desc;
    const int now = doc.undoStack()->count();
    struct Case {
      const char* field;
      double t;
      Json value;
      const char* says;
    };
    const Case cases[] = {
        {"rate_per_s", 2.0, -5.0, "rate_per_s"},
        {"rate_per_s", 2.0, std::nan(""), "rate_per_s"},
        {"rate_per_s", std::nan(""), 5.0, "Key time"},
        {"rate_per_s", 1e9, 5.0, "Key time"},
        {"wind_m_per_s", 2.0, Json::array({1.0, 2.0}), "wind_m_per_s"},
        {"drag_per_s", 2.0, 1.0, "drag_per_s"},
    };
    for (const Case& c : cases) {
      QVERIFY2(!ops::keyEmitterField(doc, id, c.field, c.t, c.value, error), c.field);
      QVERIFY2(error.find(c.says) != std::string::npos && error.find("Road dust") != std::string::npos, error.c_str());
    }
    QCOMPARE(doc.undoStack()->count(), now);
    QVERIFY(doc.state().find(id)->particles->desc == before);
  }

  void fileRoundTripKeepsEveryEmitter() {
    Document doc;
    addPreset(doc, "campfire", {.at = {3, 4, 5}, .seed = 9});
    const EntityId snow = addPreset(doc, "snow", {.area = glm::dvec4(0, 0, 50, 50), .rate = 1234.0});
    std::string error;
    QVERIFY(ops::setEmitterValue(doc, snow, "bursts", Json::parse("[[2, 100]]"), error));
    const std::string path = tempPath("round.hscene");
    QVERIFY2(saveScene(doc.state(), path, error), error.c_str());
    QCOMPARE(sceneFileVersion(path), kSceneFormatVersion);
    auto loaded = loadScene(path, error);
    QVERIFY2(loaded, error.c_str());
    size_t emitters = 0;
    for (const auto& [id, e] : doc.state().entities) {
      if (!e.particles) continue;
      ++emitters;
      const Entity* l = loaded->find(id);
      QVERIFY(l && l->particles);
      QVERIFY2(l->particles->desc == e.particles->desc, e.name.c_str());
      QVERIFY(l->transform == e.transform);
    }
    QCOMPARE(emitters, size_t(4));
  }

  // A format-10 file (before `space` and `draw_mesh`) opens with their
  // defaults and is saved as the current format.
  void format10EmittersOpenWithTheNewKeysDefaulted() {
    Document doc;
    const EntityId snow = addPreset(doc, "snow", {});
    const particles::EmitterDesc want = doc.state().find(snow)->particles->desc;
    QCOMPARE(int(want.space), int(particles::Space::Local));
    const std::string path = tempPath("format10.hscene");
    std::string error;
    QVERIFY(saveScene(doc.state(), path, error));
    {
      sqlite3* db = nullptr;
      QCOMPARE(sqlite3_open(path.c_str(), &db), SQLITE_OK);
      auto exec = [&](const std::string& sql) {
        QCOMPARE(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
        QCOMPARE(sqlite3_changes(db), 1);
      };
      exec("UPDATE document SET json = replace(replace(replace(json, '\"space\": \"local\",', ''), "
           "'\"draw_mesh\": \"\",', ''), '\"version\": " + std::to_string(kSceneFormatVersion) +
           "', '\"version\": 10') "
           "WHERE instr(json, '\"draw_mesh\": \"\",') > 0 AND instr(json, '\"space\": \"local\",') > 0");
      exec("UPDATE meta SET value = '10' WHERE key = 'format_version'");
      sqlite3_close(db);
    }
    QCOMPARE(sceneFileVersion(path), 10);
    auto loaded = loadScene(path, error);
    QVERIFY2(loaded, error.c_str());
    QVERIFY(loaded->find(snow)->particles->desc == want);
    const std::string again = tempPath("format10-saved.hscene");
    QVERIFY(saveScene(*loaded, again, error));
    QCOMPARE(sceneFileVersion(again), kSceneFormatVersion);
  }

  void damagedEmitterRefusesTheFileWithItsPath() {
    Document doc;
    addPreset(doc, "snow", {});
    const std::string path = tempPath("damaged.hscene");
    std::string error;
    QVERIFY(saveScene(doc.state(), path, error));
    {
      sqlite3* db = nullptr;
      QCOMPARE(sqlite3_open(path.c_str(), &db), SQLITE_OK);
      const char* sql = "UPDATE document SET json = replace(json, '\"drag_per_s\": 8.0', '\"drag_per_s\": \"strong\"') "
                        "WHERE instr(json, '\"drag_per_s\": 8.0') > 0";
      QCOMPARE(sqlite3_exec(db, sql, nullptr, nullptr, nullptr), SQLITE_OK);
      QCOMPARE(sqlite3_changes(db), 1);  // the snow's drag was there to damage
      sqlite3_close(db);
    }
    QVERIFY(!loadScene(path, error));
    for (const char* part : {"components.particles", "drag_per_s", "strong", "Snow"})
      QVERIFY2(error.find(part) != std::string::npos, error.c_str());
  }

  void snowSticksOnTheTerrainWithinAMillimetre() {
    Document doc;
    makeTerrain(doc);
    particles::EmitterDesc d = small(400.0);
    d.shape = particles::Shape::Box;
    d.boxHalf = {30.0, 30.0, 1.0};
    d.direction = {0, 0, -1};
    d.speedMin = 2.0, d.speedMax = 6.0;
    d.lifetimeMin = d.lifetimeMax = 8.0;
    d.collision = particles::CollisionMode::Stick;
    d.gravity = {0, 0, -9.81};
    d.drag = 0.5;
    const EntityId id = addEmitter(doc, "Flakes", {0, 0, 30}, d);
    ParticleWorld world(doc.state());
    std::string error;
    auto ev = world.evaluator(*emitterInWorld(doc.state(), id), error);
    QVERIFY2(ev, error.c_str());
    const particles::Frame f = ev->frame(6.0);
    QVERIFY(f.particles.size() > 500);
    const FoliageGround ground(doc.state(), false);
    size_t resting = 0;
    double worst = 0.0;
    for (const particles::Particle& p : f.particles) {
      const glm::dvec3 w = glm::dvec3(0, 0, 30) + p.position;
      const auto s = foliage::terrainSurface(ground.ground().terrain->height, {w.x, w.y});
      QVERIFY(s);
      worst = std::max(worst, s->position.z - w.z);
      if (p.fate == particles::Fate::Resting) {
        ++resting;
        QVERIFY2(std::abs(w.z - s->position.z) < 1e-3, std::to_string(w.z - s->position.z).c_str());
      }
    }
    QVERIFY2(worst < 1e-3, std::to_string(worst).c_str());
    QVERIFY2(resting > 100, std::to_string(resting).c_str());
  }

  // Only the colliders an emitter's particles can reach are given to it:
  // dropping the others changes no particle (the frame equals, bit for bit,
  // the one evaluated with every collider), and an emitter that can reach
  // none is not replayed at all.
  void collidersOutOfReachAreLeftOut() {
    std::string error;
    auto demo = buildDemoScene(error);
    QVERIFY2(demo, error.c_str());
    Document doc;
    doc.reset(std::move(*demo), QString());
    const FoliageGround ground(doc.state(), true);
    const foliage::MeshGround* bunny = nullptr;
    for (const foliage::MeshGround* m : ground.ground().meshes)
      if (m->triangleCount() == 69451 && glm::length(m->mesh().origin) < 50.0 && !bunny) bunny = m;
    QVERIFY(bunny);
    glm::dvec3 top(0.0, 0.0, -1e30);  // its highest vertex
    for (const glm::vec3& p : bunny->mesh().positions)
      if (bunny->mesh().origin.z + double(p.z) > top.z) top = bunny->mesh().origin + glm::dvec3(p);

    // Sparks falling onto the bunny, sticking where they land: short lives,
    // so the sphere that holds them (about 2.6 m) misses the demo's other
    // meshes.
    particles::EmitterDesc d = small(400.0);
    d.lifetimeMin = d.lifetimeMax = 0.5;
    d.speedMin = d.speedMax = 0.2;
    d.direction = {0, 0, -1};
    d.collision = particles::CollisionMode::Stick;
    d.shape = particles::Shape::Disc;
    d.radius = 0.1;
    d.gravity = {0, 0, -9.81};
    const EntityId id = addEmitter(doc, "Bunny sparks", top + glm::dvec3(0, 0, 0.3), d);
    ParticleWorld world(doc.state());
    const auto placed = emitterInWorld(doc.state(), id);
    const particles::EvaluatorInputs all = world.inputs(*placed, true, false);
    const particles::EvaluatorInputs reached = world.inputs(*placed);
    qInfo("colliders: %zu in the scene, %zu in reach", all.colliders.size(), reached.colliders.size());
    QVERIFY(all.colliders.size() >= 4);
    QVERIFY(!reached.colliders.empty() && reached.colliders.size() < all.colliders.size());
    auto pruned = particles::Evaluator::create(*placed, reached, error);
    auto every = particles::Evaluator::create(*placed, all, error);
    QVERIFY2(pruned && every, error.c_str());
    size_t resting = 0;
    for (double t : {0.7, 1.5, 2.9}) {
      const particles::Frame a = pruned->frame(t), b = every->frame(t);
      QCOMPARE(a.particles.size(), b.particles.size());
      QVERIFY(a.particles == b.particles);
      for (const particles::Particle& p : a.particles) resting += p.fate == particles::Fate::Resting;
    }
    QVERIFY2(resting > 50, qPrintable(QString::number(resting)));  // they did meet something

    // 1 km above the scene, rising: nothing in reach, no replay.
    particles::EmitterDesc up = small(50.0);
    up.collision = particles::CollisionMode::Bounce;
    up.gravity = glm::dvec3(0.0);
    up.direction = {0, 0, 1};
    const EntityId high = addEmitter(doc, "High sparks", top + glm::dvec3(0, 0, 1000.0), up);
    ParticleWorld world2(doc.state());
    const auto highPlaced = emitterInWorld(doc.state(), high);
    QVERIFY(world2.inputs(*highPlaced).colliders.empty());
    auto highEv = world2.evaluator(*highPlaced, error);
    QVERIFY2(highEv, error.c_str());
    QVERIFY(!highEv->replays());
  }

  void meshShapeIsBornOnItsEntitysSurface() {
    std::string error;
    auto demo = buildDemoScene(error);
    QVERIFY2(demo, error.c_str());
    Document doc;
    doc.reset(std::move(*demo), QString());
    particles::EmitterDesc d = small(200.0);
    d.shape = particles::Shape::Mesh;
    d.mesh = "Stanford Bunny";
    d.speedMin = d.speedMax = 0.0;
    d.gravity = glm::dvec3(0.0);
    const EntityId id = addEmitter(doc, "Bunny sparks", {1, 2, 3}, d);
    ParticleWorld world(doc.state());
    const auto placed = emitterInWorld(doc.state(), id);
    auto ev = world.evaluator(*placed, error);
    QVERIFY2(ev, error.c_str());
    const particles::Frame f = ev->frame(1.0);
    QVERIFY(f.particles.size() > 50);
    // Standing still, every particle lies on the bunny: within 1 mm of it.
    const FoliageGround ground(doc.state(), true);
    const foliage::MeshGround* bunny = nullptr;
    for (const foliage::MeshGround* m : ground.ground().meshes)
      if (m->triangleCount() == 69451 && glm::length(m->mesh().origin) < 50.0 && !bunny) bunny = m;
    QVERIFY(bunny);
    for (const particles::Particle& p : f.particles) {
      const auto c = bunny->closest(placed->origin + p.position, 0.01);
      QVERIFY2(c && glm::length(c->position - (placed->origin + p.position)) < 1e-3, "off the surface");
    }
    // A name no visible mesh entity has: refused, naming it.
    std::string why;
    QVERIFY(ops::setEmitterValue(doc, id, "mesh", "Monastery roof", why));
    QVERIFY(!world.evaluator(*emitterInWorld(doc.state(), id), why));
    QVERIFY2(why.find("Monastery roof") != std::string::npos, why.c_str());
  }

  void utmPositionsStayFiniteAndExact() {
    Document doc;
    const glm::dvec3 utm(500000.0, 4400000.0, 300.0);
    const EntityId torch = addPreset(doc, "torch", {.at = utm});
    for (EntityId c : doc.state().find(torch)->children) {
      const auto d = emitterInWorld(doc.state(), c);
      QVERIFY2(glm::length(d->origin - utm) < 2.0, "flame at the torch, smoke just above");
      ParticleWorld world(doc.state());
      std::string error;
      auto ev = world.evaluator(*d, error);
      QVERIFY2(ev, error.c_str());
      const particles::Frame f = ev->frame(12.25);
      QVERIFY(!f.particles.empty());
      for (const particles::Particle& p : f.particles) {
        QVERIFY(std::isfinite(p.position.x) && std::isfinite(p.position.y) && std::isfinite(p.position.z));
        QVERIFY2(glm::length(p.position) < 50.0, "a torch's particles stay near it");
      }
    }
  }

  void liveCountsMatchTheEvaluatedFrame() {
    Document doc;
    const EntityId a = addEmitter(doc, "A", {0, 0, 0}, small(50.0));
    particles::EmitterDesc late = small(10.0);
    late.start = 5.0;
    const EntityId b = addEmitter(doc, "B", {5, 0, 0}, late);
    const EntityId hidden = addEmitter(doc, "Hidden", {9, 0, 0}, small(10.0));
    QVERIFY(ops::setField(doc, hidden, *findEntityField("entity.visible"), FieldValue(false)));
    for (double t : {0.0, 1.0, 3.0, 6.0}) {
      const std::vector<EmitterCount> counts = liveParticleCounts(doc.state(), t);
      QCOMPARE(counts.size(), size_t(2));  // the hidden one is not listed
      for (const EmitterCount& c : counts) {
        QVERIFY(c.error.empty());
        ParticleWorld world(doc.state());
        std::string error;
        auto ev = world.evaluator(*emitterInWorld(doc.state(), c.entity), error);
        QCOMPARE(c.live, uint64_t(ev->frame(t).particles.size()));
      }
      QCOMPARE(counts[0].entity, a);
      QCOMPARE(counts[1].entity, b);
    }
    QCOMPARE(liveParticleCounts(doc.state(), 3.0)[1].live, uint64_t(0));  // B starts at 5 s
  }

  // World space: a particle starts where the emitter was at its birth and
  // stays there (no forces, no speed) while the entity moves on; local
  // space: it moves along. The emitter's motion agrees with the scene's
  // animation at every time, through a parent and through a camera path.
  void worldSpaceLeavesParticlesWhereTheyWereBorn() {
    Document doc;
    particles::EmitterDesc d = small(4.0);
    d.speedMin = d.speedMax = 0.0;
    d.gravity = glm::dvec3(0.0);
    d.lifetimeMin = d.lifetimeMax = 10.0;
    d.origin = {0.0, 0.0, 1.5};  // an offset above the entity
    d.space = particles::Space::World;
    const EntityId parent = ops::addEmpty(doc, "Cart", Transform{});
    const EntityId torch = addEmitter(doc, "Torch", {0, 0, 0}, d);
    QVERIFY(ops::reparent(doc, torch, parent));
    moveLinearly(doc, parent, {0, 0, 0}, {40, 8, 0});
    const SceneState& base = doc.state();
    for (double t : {0.5, 2.0, 3.75}) {
      const SceneState at = animatedState(base, compileSequence(base), t);
      const std::vector<PlacedEmitter> placed = visibleEmitters(at);
      QCOMPARE(placed.size(), size_t(1));
      QVERIFY(placed[0].motion);
      for (double tb : {0.0, 0.3, 1.7, t})
        QVERIFY(glm::length(placed[0].motion->originAt(tb) - (animatedWorld(base, torch, tb) + d.origin)) < 1e-9);
      ParticleWorld world(at);
      std::string error;
      auto ev = world.evaluator(placed[0], error);
      QVERIFY2(ev, error.c_str());
      const particles::Frame f = ev->frame(t);
      QVERIFY(f.particles.size() >= 2);
      for (const particles::Particle& p : f.particles) {
        const glm::dvec3 worldPos = placed[0].desc.origin + p.position;
        const glm::dvec3 bornAt = animatedWorld(base, torch, p.birth) + d.origin;
        QVERIFY2(glm::length(worldPos - bornAt) < 1e-9, qPrintable(QString::number(glm::length(worldPos - bornAt))));
      }
      // Local space: every particle is at the emitter's current origin.
      PlacedEmitter local = placed[0];  // its motion kept: local space ignores it
      local.desc.space = particles::Space::Local;
      auto lev = world.evaluator(local, error);
      for (const particles::Particle& p : lev->frame(t).particles) QVERIFY(glm::length(p.position) < 1e-12);
    }
    // Local space on the entity: no motion is derived (nothing to pay for).
    std::string why;
    QVERIFY(ops::setEmitterValue(doc, torch, "space", Json("local"), why));
    QVERIFY(!EmitterMotion::of(doc.state(), torch));
    QVERIFY(ops::setEmitterValue(doc, torch, "space", Json("world"), why));
    QVERIFY(EmitterMotion::of(doc.state(), torch));
    // A still chain has no motion either.
    Document still;
    const EntityId s = addEmitter(still, "Still", {1, 2, 3}, d);
    QVERIFY(!EmitterMotion::of(still.state(), s));

    // Through a camera path on the parent.
    QVERIFY(ops::setPath(doc, parent, sequencer::makePathFollow({{0, 0, 0}, {20, 0, 0}, {20, 20, 0}}, 0.0, 4.0),
                         "Follow path"));
    const auto motion = EmitterMotion::of(doc.state(), torch);
    QVERIFY(motion);
    for (double tb : {0.0, 1.1, 2.5, 4.0})
      QVERIFY2(glm::length(motion->originAt(tb) - (animatedWorld(doc.state(), torch, tb) + d.origin)) < 1e-9,
               qPrintable(QString::number(glm::length(motion->originAt(tb) - (animatedWorld(doc.state(), torch, tb) + d.origin)))));
  }

  // The bound an out-of-view test uses (scene::placedBound) for a
  // world-space emitter on a moving chain (a cubic move that overshoots its
  // keys, under a parent that turns and scales) with speed, size and radius
  // keyed on the timeline: the origin box holds the origin at every birth
  // time that matters, and the bound every particle a brute-force
  // evaluation finds, with sizes and speeds under the widened emitter's.
  // Without the widening some particles lie outside (the test can tell).
  // A camera path in the chain (its curve overshooting its points) too.
  void boundsFollowTheMotionAndTheSpawnTracks() {
    Document doc;
    particles::EmitterDesc d = small(25.0);
    d.shape = particles::Shape::Sphere;
    d.radius = 0.5;
    d.speedMin = 1.0, d.speedMax = 2.0;
    d.sizeMin = 0.1, d.sizeMax = 0.2;
    d.lifetimeMin = 1.0, d.lifetimeMax = 3.0;
    d.spreadDeg = 60.0;
    d.gravity = glm::dvec3(0.0);  // the travel is the speed's alone: the widening shows
    d.drag = 0.0;
    d.origin = {0.0, 0.0, 1.5};
    d.space = particles::Space::World;
    const EntityId rig = ops::addEmpty(doc, "Rig", Transform{});
    const EntityId cart = ops::addEmpty(doc, "Cart", Transform{});
    const EntityId torch = addEmitter(doc, "Torch", {0, 0, 0}, d);
    QVERIFY(ops::reparent(doc, torch, cart) && ops::reparent(doc, cart, rig));
    {
      Edit e(doc, "Animate");
      sequencer::Binding moves;
      moves.entity = cart;
      sequencer::VectorTrack move;
      move.property = "transform.translation";
      sequencer::VectorKey k0, k1, k2;
      k0.time = 0.0, k0.value = {0, 0, 0};
      k0.setSlope({30, -20, 0});  // overshoots backwards in y
      k1.time = 4.0, k1.value = {40, 8, 0};
      k2.time = 6.0, k2.value = {40, 20, 5};
      move.keys = {k0, k1, k2};
      moves.tracks.push_back(move);
      sequencer::Binding turns;
      turns.entity = rig;
      sequencer::RotationTrack turn;
      sequencer::RotationKey r0, r1;
      r0.time = 0.0, r0.interpolation = sequencer::Interpolation::Linear;
      r1.time = 5.0, r1.value = glm::angleAxis(glm::radians(120.0), glm::dvec3(0, 0, 1));
      turn.keys = {r0, r1};
      sequencer::VectorTrack grow;
      grow.property = "transform.scale";
      sequencer::VectorKey s0, s1;
      s0.time = 0.0, s0.value = glm::dvec3(1.0), s0.interpolation = sequencer::Interpolation::Linear;
      s1.time = 5.0, s1.value = glm::dvec3(2.0);
      grow.keys = {s0, s1};
      turns.tracks = {turn, grow};
      e.sequence().bindings.push_back(moves);
      e.sequence().bindings.push_back(turns);
      e.commit();
    }
    std::string error;
    for (auto [key, values] : {std::pair{"particles.speed_m_per_s", std::pair{1.5, 6.0}},
                               std::pair{"particles.size_m", std::pair{0.15, 0.6}},
                               std::pair{"particles.radius_m", std::pair{0.5, 3.0}}}) {
      const auto target = animationTarget(key, error);
      QVERIFY2(target, error.c_str());
      QVERIFY(ops::setKeys(doc, {{torch, *target, sequencer::PropertyValue(values.first)}}, 0.0, std::nullopt, "Key"));
      QVERIFY(ops::setKeys(doc, {{torch, *target, sequencer::PropertyValue(values.second)}}, 4.0, std::nullopt, "Key"));
    }
    {
      // A steep user slope: the speed track overshoots its last key.
      Edit e(doc, "Slope");
      for (sequencer::Track& t : e.sequence().findBinding(torch)->tracks)
        if (auto* sc = std::get_if<sequencer::ScalarTrack>(&t); sc && sc->property == "particles.speed_m_per_s")
          sc->keys[0].setSlope(5.0);
      e.commit();
    }
    size_t n = 0, outsideUnwidened = 0;
    double farthest = 0.0;
    // At 12 s the chain has been still for the whole live window (the box
    // is a point): what is left is the spawn tracks' widening.
    for (double t : {0.5, 2.0, 3.5, 5.5, 8.0, 12.0}) {
      const SceneState at = animatedState(doc.state(), compileSequence(doc.state()), t);
      const std::vector<PlacedEmitter> placed = visibleEmitters(at);
      QVERIFY(placed.size() == 1 && placed[0].motion && placed[0].spawn);
      const PlacedEmitter& pe = placed[0];
      ParticleWorld world(at);
      const std::optional<PlacedBound> b = placedBound(pe, t, &world, nullptr);
      QVERIFY(b);
      const std::optional<particles::OriginBox> box = pe.motion->originRange(t - d.lifetimeMax, t);
      QVERIFY(box);
      for (int i = 0; i <= 3000; ++i) {
        const glm::dvec3 o = pe.motion->originAt(t - d.lifetimeMax * i / 3000.0);
        QVERIFY2(glm::all(glm::lessThanEqual(box->lo, o)) && glm::all(glm::lessThanEqual(o, box->hi)),
                 qPrintable(QString("t %1, birth %2: origin %3 %4 %5 outside %6 %7 %8 .. %9 %10 %11")
                                .arg(t).arg(t - d.lifetimeMax * i / 3000.0).arg(o.x).arg(o.y).arg(o.z)
                                .arg(box->lo.x).arg(box->lo.y).arg(box->lo.z).arg(box->hi.x).arg(box->hi.y).arg(box->hi.z)));
      }
      particles::BoundInputs plain;
      plain.moves = true;
      plain.birthOrigins = box;
      const std::optional<particles::ParticleBound> unwidened = particles::particleBound(pe.desc, plain);
      auto ev = world.evaluator(pe, error);
      QVERIFY2(ev, error.c_str());
      for (const particles::Particle& p : ev->frame(t).particles) {
        const double share = glm::length(p.position - b->bound.centre) / b->bound.radius;
        QVERIFY2(share <= 1.0 + 1e-12, qPrintable(QString("t %1: %2 of the radius").arg(t).arg(share)));
        QVERIFY(p.size <= b->desc.sizeMax * (1.0 + 1e-12));
        QVERIFY(glm::length(p.velocity) <= particles::speedBound(b->desc, p.age) * (1.0 + 1e-12));
        farthest = std::max(farthest, share);
        if (glm::length(p.position - unwidened->centre) > unwidened->radius) ++outsideUnwidened;
        ++n;
      }
    }
    qInfo("%zu particles inside their bound (farthest at %.3f of its radius); %zu outside the unwidened one", n,
          farthest, outsideUnwidened);
    QVERIFY(n > 200 && outsideUnwidened > 0);
    // A camera path moving the chain (a turn that overshoots its points,
    // the aim turning the torch's offset under the cart): the box holds
    // the origin at every birth time, and the bound every particle.
    QVERIFY(ops::setPath(doc, cart, sequencer::makePathFollow({{0, 0, 0}, {20, 0, 0}, {20, 20, 0}, {0, 22, 3}}, 0.0, 4.0),
                         "Follow path"));
    {
      Edit e(doc, "Offset");
      e.entity(torch).transform.translation = {0.0, 2.0, 0.5};  // turned by the path's aim
      e.commit();
    }
    size_t onPath = 0;
    for (double t : {1.0, 2.5, 4.5}) {
      const SceneState at = animatedState(doc.state(), compileSequence(doc.state()), t);
      const std::vector<PlacedEmitter> placed = visibleEmitters(at);
      QVERIFY(placed.size() == 1 && placed[0].motion);
      const std::optional<particles::OriginBox> box = placed[0].motion->originRange(t - d.lifetimeMax, t);
      QVERIFY(box);
      for (int i = 0; i <= 1000; ++i) {
        const glm::dvec3 o = placed[0].motion->originAt(t - d.lifetimeMax * i / 1000.0);
        QVERIFY2(glm::all(glm::lessThanEqual(box->lo, o)) && glm::all(glm::lessThanEqual(o, box->hi)),
                 qPrintable(QString("t %1: origin %2 %3 %4 outside the path's box").arg(t).arg(o.x).arg(o.y).arg(o.z)));
      }
      ParticleWorld world(at);
      const std::optional<PlacedBound> b = placedBound(placed[0], t, &world, nullptr);
      QVERIFY(b);
      auto ev = world.evaluator(placed[0], error);
      QVERIFY2(ev, error.c_str());
      for (const particles::Particle& p : ev->frame(t).particles) {
        QVERIFY(glm::length(p.position - b->bound.centre) <= b->bound.radius * (1.0 + 1e-12));
        ++onPath;
      }
    }
    QVERIFY(onPath > 50);
  }

  // A spawn value keyed on the timeline: each particle takes the track's
  // value at its birth (a pair's centre moves, its half-width stays) and
  // keeps it; the entity itself is not animated by it; a file keeps the
  // track and drops one on a field that is not a spawn value, naming it.
  void spawnValuesKeyedOnTheTimelineAreSampledAtBirth() {
    Document doc;
    particles::EmitterDesc d = small(10.0);
    d.sizeMin = 0.1, d.sizeMax = 0.3;  // centre 0.2, half-width 0.1
    d.lifetimeMin = d.lifetimeMax = 20.0;
    d.gravity = glm::dvec3(0.0);  // velocities keep their birth direction
    const EntityId id = addEmitter(doc, "Puff", {0, 0, 0}, d);
    std::string error;
    const auto target = animationTarget("particles.size_m", error);
    QVERIFY2(target && target->kind == TrackKind::Scalar, error.c_str());
    QVERIFY(!animationTarget("particles.drag_per_s", error));
    QVERIFY2(error.find("spawn values") != std::string::npos, error.c_str());
    for (auto [t, v] : {std::pair{0.0, 0.2}, std::pair{10.0, 1.2}})
      QVERIFY(ops::setKeys(doc, {{id, *target, sequencer::PropertyValue(v)}}, t, sequencer::Interpolation::Linear,
                           "Key size"));
    auto centreAt = [](double birth) { return 0.2 + 0.1 * std::clamp(birth, 0.0, 10.0); };
    std::map<uint64_t, double> sizeAt8;
    for (double t : {8.0, 12.0}) {
      std::vector<std::string> warnings;
      const SceneState at = animatedState(doc.state(), compileSequence(doc.state()), t, &warnings);
      QVERIFY2(warnings.empty(), warnings.empty() ? "" : warnings[0].c_str());
      QCOMPARE(at.find(id)->particles->desc.sizeMin, 0.1);  // not written at the frame's time
      const std::vector<PlacedEmitter> placed = visibleEmitters(at);
      QVERIFY(placed.size() == 1 && placed[0].spawn);
      ParticleWorld world(at);
      auto keyed = world.evaluator(placed[0], error);
      auto plain = world.evaluator(placed[0].desc, error);  // the same emitter without its track
      QVERIFY2(keyed && plain, error.c_str());
      const particles::Frame fk = keyed->frame(t), fp = plain->frame(t);
      QCOMPARE(fk.particles.size(), fp.particles.size());
      QVERIFY(fk.particles.size() > 50);
      for (size_t i = 0; i < fk.particles.size(); ++i) {
        const particles::Particle &k = fk.particles[i], &p = fp.particles[i];
        QCOMPARE(k.id, p.id);
        // The same random draw, about a centre moved by the track.
        QVERIFY(std::abs((k.size - p.size) - (centreAt(k.birth) - 0.2)) < 1e-12);
        if (t == 8.0) sizeAt8[k.id.index] = k.size;
        else if (sizeAt8.count(k.id.index)) QCOMPARE(k.size, sizeAt8[k.id.index]);  // kept, not moved by later keys
      }
    }
    QVERIFY(!sizeAt8.empty());
    // A direction track turns the particles born after it.
    const auto dir = animationTarget("particles.direction", error);
    QVERIFY(dir && dir->kind == TrackKind::Vector);
    QVERIFY(ops::setKeys(doc, {{id, *dir, sequencer::PropertyValue(glm::dvec3(1, 0, 0))}}, 0.0, std::nullopt, "Key"));
    {
      const SceneState at = animatedState(doc.state(), compileSequence(doc.state()), 3.0);
      ParticleWorld world(at);
      auto ev = world.evaluator(visibleEmitters(at)[0], error);
      for (const particles::Particle& p : ev->frame(3.0).particles)
        QVERIFY(glm::length(glm::normalize(p.velocity) - glm::dvec3(1, 0, 0)) < 1e-9);
    }

    // The file keeps the tracks; one on a field that is not a spawn value is dropped, named.
    {
      Edit e(doc, "Bad track");
      sequencer::ScalarTrack bad;
      bad.property = "particles.drag_per_s";
      bad.keys.push_back({});
      e.sequence().findBinding(id)->tracks.push_back(bad);
      e.commit();
    }
    const std::string path = tempPath("spawn-tracks.hscene");
    QVERIFY2(saveScene(doc.state(), path, error), error.c_str());
    LoadReport report;
    const auto loaded = loadScene(path, error, nullptr, &report);
    QVERIFY2(loaded, error.c_str());
    const sequencer::Binding* b = loaded->sequence.findBinding(id);
    QVERIFY(b);
    std::vector<std::string> props;
    for (const sequencer::Track& t : b->tracks) props.push_back(sequencer::trackProperty(t));
    QVERIFY(std::find(props.begin(), props.end(), "particles.size_m") != props.end());
    QVERIFY(std::find(props.begin(), props.end(), "particles.direction") != props.end());
    QVERIFY(std::find(props.begin(), props.end(), "particles.drag_per_s") == props.end());
    bool named = false;
    for (const std::string& w : report.warnings) named = named || (w.find("particles.drag_per_s") != std::string::npos &&
                                                                   w.find("Puff") != std::string::npos);
    QVERIFY(named);
  }

  void demoHasSnowFogAndATorch() {
    std::string error;
    auto demo = buildDemoScene(error);
    QVERIFY2(demo, error.c_str());
    std::vector<std::string> names;
    for (const PlacedEmitter& p : visibleEmitters(*demo)) names.push_back(p.desc.name);
    QVERIFY(std::find(names.begin(), names.end(), "Snow") != names.end());
    QVERIFY(std::find(names.begin(), names.end(), "Fog bank") != names.end());
    QVERIFY(std::find(names.begin(), names.end(), "Monastery torch flame") != names.end());
    QVERIFY(std::find(names.begin(), names.end(), "Monastery torch smoke") != names.end());
    // Something to see at the first frame: every emitter is already running.
    for (const EmitterCount& c : liveParticleCounts(*demo, 0.0)) {
      QVERIFY2(c.error.empty(), c.error.c_str());
      QVERIFY2(c.live > 0, c.name.c_str());
    }
    // The snow thickens: its size keyed from the field's own centre at 0 s
    // (the first frame is the unkeyed one) to twice it at 20 s.
    const EntityId snow = demo->findByName("Snow");
    const auto tracks = EmitterSpawnTracks::of(*demo, snow);
    QVERIFY(tracks);
    particles::SpawnValues early = particles::spawnValues(demo->find(snow)->particles->desc), late = early;
    const particles::SpawnValues unkeyed = early;
    tracks->apply(0.0, early);
    tracks->apply(20.0, late);
    QCOMPARE(early.sizeMin, unkeyed.sizeMin);
    QCOMPARE(early.sizeMax, unkeyed.sizeMax);
    QVERIFY(std::abs(0.5 * (late.sizeMin + late.sizeMax) - 2.0 * 0.5 * (unkeyed.sizeMin + unkeyed.sizeMax)) < 1e-12);
  }
};

QTEST_GUILESS_MAIN(TestSceneParticles)
#include "test_scene_particles.moc"

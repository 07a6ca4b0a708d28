#include "scene/demo_scene.h"

#include <QFile>

#include "mesh/mesh_import.h"
#include "scene/report_json.h"

namespace hs::scene {
namespace {

EntityId add(SceneState& s, Entity e, EntityId parent = kNoEntity) {
  e.id = s.maxEntityId() + 1;
  e.parent = parent;
  if (parent == kNoEntity)
    s.roots.push_back(e.id);
  else
    s.entities[parent].children.push_back(e.id);
  const EntityId id = e.id;
  s.entities.emplace(id, std::move(e));
  return id;
}

Transform at(glm::dvec3 t, glm::dvec3 eulerDeg = {0, 0, 0}, double scale = 1.0) {
  Transform x;
  x.translation = t;
  x.rotation = fromEulerDegrees(eulerDeg);
  x.scale = glm::dvec3(scale);
  return x;
}

}  // namespace

SceneState buildStarterScene() {
  SceneState s;
  Entity sun;
  sun.name = "Sun";
  sun.transform = at({0, 0, 20}, {40, 0, -35});
  sun.light = Light{};
  add(s, sun);
  Entity cam;
  cam.name = "Camera";
  cam.transform = at({0.0, -12.0, 4.0}, {75, 0, 0});
  cam.camera = Camera{};
  add(s, cam);
  return s;
}

std::optional<SceneState> buildDemoScene(std::string& error) {
  QFile f(":/demo/stanford-bunny.obj");
  if (!f.open(QIODevice::ReadOnly)) {
    error = "the demo's bunny mesh is missing from this build (resource :/demo/stanford-bunny.obj)";
    return std::nullopt;
  }
  const QByteArray bytes = f.readAll();
  mesh::ImportResult bunny =
      mesh::importObjFromMemory({bytes.constData(), size_t(bytes.size())}, "stanford-bunny.obj", ":/demo");
  if (!bunny.ok()) {
    error = "demo scene: " + bunny.error;
    return std::nullopt;
  }

  SceneState s;
  // The scan sits at its own origin; the asset keeps it there.
  MeshAsset asset;
  asset.id = 1;
  asset.name = "Stanford Bunny";
  asset.sourcePath = "resources/demo/stanford-bunny.obj";
  asset.contentHash = mesh::contentHash(*bunny.mesh);
  asset.importReportJson = importReportToJson(bunny.report);
  const mesh::Bounds b = bunny.mesh->bounds();
  asset.data = std::make_shared<const mesh::MeshData>(std::move(*bunny.mesh));
  s.assets.emplace(asset.id, asset);

  Entity sun;
  sun.name = "Sun";
  // Shines along local -Z: tilted 50 degrees from vertical, from the south-west.
  sun.transform = at({0, 0, 20}, {40, 0, -35});
  sun.light = Light{};
  add(s, sun);

  Entity cam;
  cam.name = "Main Camera";
  // Pitched up from looking straight down (local -Z) to 12 degrees below the horizon.
  cam.transform = at({0.0, -9.0, 2.6}, {78, 0, 0});
  cam.camera = Camera{};
  cam.camera->verticalFovDeg = 40.0;
  add(s, cam);

  Entity group;
  group.name = "Scans";
  const EntityId scans = add(s, group);

  // The scan scaled up 12x (it was scanned in metres, 0.15 m tall), standing
  // on the ground: base of its bounding box at z = 0.
  const double scale = 12.0;
  const glm::dvec3 base(b.center().x, b.center().y, b.min.z);
  Entity big;
  big.name = "Stanford Bunny";
  big.transform = at(-base * scale, {0, 0, 20}, scale);
  big.mesh = MeshInstance{asset.id};
  add(s, big, scans);

  // Two instances of the same asset: one mesh in memory, drawn three times.
  Entity left;
  left.name = "Bunny (instance, tinted)";
  left.transform = at(glm::dvec3(-3.2, 1.5, 0) - base * 6.0, {0, 0, 60}, 6.0);
  left.mesh = MeshInstance{asset.id, glm::vec3(0.95f, 0.55f, 0.35f)};
  add(s, left, scans);

  Entity right;
  right.name = "Bunny (instance)";
  right.transform = at(glm::dvec3(3.4, 2.5, 0) - base * 8.0, {0, 0, -40}, 8.0);
  right.mesh = MeshInstance{asset.id, glm::vec3(0.55f, 0.75f, 0.95f)};
  add(s, right, scans);

  if (const std::string problem = s.validate(); !problem.empty()) {
    error = "demo scene is inconsistent: " + problem;
    return std::nullopt;
  }
  return s;
}

}  // namespace hs::scene

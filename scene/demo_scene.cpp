#include "scene/demo_scene.h"

#include <cmath>
#include <utility>

#include <QFile>

#include "mesh/mesh_import.h"
#include "meshproc/mesh_process.h"
#include "scene/asset_reports.h"
#include "scene/camera_post.h"
#include "scene/demo_clusters.h"
#include "scene/demo_dof.h"
#include "scene/demo_lights.h"
#include "scene/demo_foliage.h"
#include "scene/demo_glass.h"
#include "scene/demo_materials.h"
#include "scene/demo_particles.h"
#include "scene/demo_post.h"
#include "scene/demo_terrain.h"
#include "scene/mesh_materials.h"
#include "scene/object_tracks.h"
#include "scene/transform.h"

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

// A keyframed stereo camera flight: 10 s at 60 fps along a camera path
// around the bunnies (off-axis stereo, the interaxial widening as the camera
// swings round), and the blue bunny turning once on a rotation track. The
// rig keeps every frame inside the default comfort budget (-1% .. +2%):
// 40 degrees vertical at 16:9, convergence 8 m, interaxial 7 to 10 cm;
// measured with `render --comfort` every 10th frame: nearest -0.90% (the
// ground 3.9 m away at about 6.2 s), farthest +0.97% (the sky at the end).
void addStereoFlight(SceneState& s, EntityId spinning, const glm::dvec3& spinCentre) {
  Entity cam;
  cam.name = "Flight Camera";
  cam.camera = Camera{};
  cam.camera->verticalFovDeg = 40.0;
  cam.camera->stereo = Camera::Stereo::OffAxis;
  cam.camera->interaxial = 0.07;
  cam.camera->convergence = 8.0;
  const glm::dvec3 centre(0.3, 1.2, 0.0);
  sequencer::PathFollow follow;
  // Three quarters of a circle of 8 m radius, rising and falling.
  const double heights[] = {1.8, 2.3, 2.8, 2.4, 1.9, 2.3, 2.7};
  for (int i = 0; i < 7; ++i) {
    const double a = glm::radians(-150.0 + 45.0 * i);
    follow.path.points.push_back(centre + glm::dvec3(8.0 * std::cos(a), 8.0 * std::sin(a), heights[i]));
  }
  follow.aim = sequencer::PathAim::Point;
  follow.targetPoint = centre + glm::dvec3(0.0, 0.0, 0.9);
  // The path drives the pose; the entity's own transform is the first
  // frame's, so the camera sits where the flight starts in any view.
  cam.transform.translation = follow.path.points.front();
  cam.transform.rotation = sequencer::lookRotation(follow.targetPoint - follow.path.points.front());
  const EntityId id = add(s, cam);

  sequencer::ScalarKey start, end;
  start.time = 0.0;
  start.value = 0.0;
  start.interpolation = sequencer::Interpolation::Linear;
  start.ease = sequencer::Ease::InOut;  // constant speed in between, soft start and stop
  end.time = 10.0;
  end.value = 1.0;
  follow.progress.keys = {start, end};

  sequencer::Binding flight{id, cam.name, {}, follow};
  sequencer::ScalarTrack interaxial{"camera.interaxial_m", {}};
  sequencer::ScalarKey i0, i1;
  i0.time = 0.0;
  i0.value = 0.07;
  i1.time = 10.0;
  i1.value = 0.10;
  interaxial.keys = {i0, i1};
  flight.tracks.push_back(interaxial);

  // The blue bunny turns once on the spot. Its entity origin is the scan's
  // origin, not the bunny's base, so a translation track keeps the base
  // centre P where it stands: T(t) = P - R(t) (scale base), keyed
  // every 30 degrees.
  const Entity& bunny = s.entities.at(spinning);
  sequencer::Binding spin{spinning, bunny.name, {}, std::nullopt};
  sequencer::RotationTrack turn;
  sequencer::VectorTrack stay{"transform.translation", {}};
  const glm::dquat r0 = bunny.transform.rotation;  // frame 0 shows it as placed
  const glm::dvec3 offset = glm::conjugate(r0) * (bunny.transform.translation - spinCentre);
  for (int i = 0; i <= 12; ++i) {
    const glm::dquat r = glm::angleAxis(glm::radians(30.0 * i), glm::dvec3(0, 0, 1)) * r0;
    sequencer::RotationKey k;
    k.time = 10.0 * i / 12.0;
    k.value = r;
    k.interpolation = sequencer::Interpolation::Linear;
    turn.keys.push_back(k);
    sequencer::VectorKey t;
    t.time = k.time;
    t.value = spinCentre + r * offset;
    stay.keys.push_back(t);
  }
  spin.tracks.push_back(turn);
  spin.tracks.push_back(stay);

  s.sequence.rate = {60, 1};
  s.sequence.startFrame = 0;
  s.sequence.endFrame = 599;
  s.sequence.bindings = {flight, spin};
}

// A short time-of-day change over the flight: the sun sinks from 50 to 35
// degrees above the horizon and swings 20 degrees west in the 10 s, so the
// analytic sky warms and the light rakes a little more by the end (visible,
// not a sunset). Frame 0 is the sun as placed, so the first camera's view
// does not depend on the track.
void addTimeOfDay(SceneState& s, EntityId sunId) {
  const Entity& sun = s.entities.at(sunId);
  sequencer::Binding b{sunId, sun.name, {}, std::nullopt};
  sequencer::RotationTrack turn;
  const glm::dvec3 euler[3] = {{40, 0, -35}, {47, 0, -45}, {55, 0, -55}};
  for (int i = 0; i < 3; ++i) {
    sequencer::RotationKey k;
    k.time = 5.0 * i;
    k.value = fromEulerDegrees(euler[i]);
    k.interpolation = sequencer::Interpolation::Linear;
    turn.keys.push_back(k);
  }
  b.tracks.push_back(turn);
  s.sequence.bindings.push_back(b);
}

// Material and settings tracks (scene/object_tracks.h) over the flight:
// the parallax slab's relief flattens and comes back (height scale 6 cm ->
// 1 cm at 5 s -> 6 cm), and the valley's depth-cue fog thickens (k2 1/400
// -> 1/200 per metre: half the colour kept at 1 km instead of 2 km). The
// first keys are the values as placed, so frame 0 and every un-animated
// render (the demo goldens) look as before.
void addDemoParameterTracks(SceneState& s) {
  auto key = [](double t, double v) {
    sequencer::ScalarKey k;
    k.time = t;
    k.value = v;
    return k;
  };
  const MaterialId slab = s.findMaterialByName("Rock slab (parallax) / surface");
  if (const Material* m = s.findMaterial(slab)) {
    sequencer::ScalarTrack relief{std::string(kMaterialTrackPrefix) + "height_scale", {}};
    relief.keys = {key(0.0, double(m->heightScale)), key(5.0, 0.01), key(10.0, double(m->heightScale))};
    s.sequence.bindings.push_back(sequencer::Binding{materialTarget(slab), m->name, {relief}, std::nullopt});
  }
  sequencer::ScalarTrack fog{std::string(kSettingsTrackPrefix) + "fog_k2", {}};
  fog.keys = {key(0.0, double(s.settings.fogK2)), key(10.0, 1.0 / 200.0)};
  s.sequence.bindings.push_back(sequencer::Binding{settingsTarget(), "Settings", {fog}, std::nullopt});
}

// The bunny's LOD chain (three levels of a quarter each: 17k, 4.3k, 1.1k
// triangles), each with its measured Hausdorff error, so the instances the
// camera sees from afar draw coarser levels. Built once per process (the
// editor, the CLI and the tests build the demo many times; the result is
// deterministic) and shared like any immutable mesh.
struct DemoLods {
  std::vector<MeshLod> lods;
  Json report;  // AssetProcessReport
};

const DemoLods& bunnyLods(const mesh::MeshData& bunny) {
  static const DemoLods built = [&] {
    mesh::ProcessOptions o;
    o.clean = false;  // the level 0 the scene has always shown stays as it is
    o.lodLevels = 3;
    // Fewer samples than an import's 10 per face: the demo is built at every
    // editor start. One per face (every vertex is measured too) keeps the
    // levels' errors within a few percent of 10 per face and halves the
    // build (0.5 s for the chain on this project's 2 cores, quiet).
    o.error.samplesPerFace = 1;
    mesh::ProcessResult r = mesh::processMesh(bunny, o);
    DemoLods d;
    if (!r.ok()) return d;  // the scene still works, at full resolution
    for (size_t k = 0; k < r.lods.size(); ++k) {
      MeshLod l;
      l.contentHash = mesh::contentHash(r.lods[k]);
      l.triangles = r.lods[k].triangleCount();
      l.hausdorff = r.report.lods.at(k + 1).hausdorff;
      l.data = std::make_shared<const mesh::MeshData>(std::move(r.lods[k]));
      d.lods.push_back(std::move(l));
    }
    d.report = toJson(AssetProcessReport{r.report, o, std::nullopt});
    return d;
  }();
  return built;
}

}  // namespace

SceneState buildStarterScene() {
  SceneState s;
  Entity sun;
  sun.name = "Sun";
  sun.transform = at({0, 0, 20}, {40, 0, -35});
  sun.light = Light{};
  sun.light->castsShadows = true;  // once settings.shadows is on
  add(s, sun);
  s.settings.sky = SkyModel::Analytic;  // new scenes get the analytic sky (old files keep the gradient)
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
  asset.importReport = toJson(AssetImportReport{bunny.report, {}});
  const DemoLods& lods = bunnyLods(*bunny.mesh);
  asset.lods = lods.lods;
  asset.processReport = lods.report;
  const mesh::Bounds b = bunny.mesh->bounds();
  asset.data = std::make_shared<const mesh::MeshData>(std::move(*bunny.mesh));
  s.assets.emplace(asset.id, asset);
  addMeshMaterials(s, asset.id);  // "Stanford Bunny / default", as an import makes

  Entity sun;
  sun.name = "Sun";
  // Shines along local -Z: tilted 50 degrees from vertical, from the south-west.
  sun.transform = at({0, 0, 20}, {40, 0, -35});
  sun.light = Light{};
  const EntityId sunId = add(s, sun);
  s.settings.sky = SkyModel::Analytic;

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
  const EntityId spinning = add(s, right, scans);

  // Added last, after everything the first camera sees, so the demo's
  // first camera and its view stay what they were (golden images use them).
  addStereoFlight(s, spinning, right.transform.translation + right.transform.rotation * (base * 8.0));
  addTimeOfDay(s, sunId);

  // The valley the bunnies stand in (flat where they are), added last too.
  if (!addDemoTerrain(s, error)) return std::nullopt;
  // A normal-mapped and a parallax-mapped material, south of the bunnies.
  addDemoDetailSamples(s);
  // Sun shadows (docs/rendering.md "Shadows"): medium quality, cascades
  // over 500 m (the 320 m valley seen from anywhere in the flight).
  s.settings.shadows = true;
  s.settings.shadowDistance = 500.0;
  // A spot and two point lights by the bunnies, and fog on the valley.
  addDemoLights(s);
  // A material parameter and the fog animated over the flight.
  addDemoParameterTracks(s);
  // The flight camera's focus pulled over the flight (depth of field; off in the demo).
  addDemoFocusPull(s);
  // Shadows (docs/rendering.md "Shadows"): the sun casts, and so does the
  // spot (the lantern's bunny shadow falls on the clearing); each light's
  // casts_shadows is read, settings.shadows is the master switch.
  for (auto& [id, e] : s.entities)
    if (e.light && e.light->type != Light::Type::Point) e.light->castsShadows = true;
  // Glass spheres and a pond, drawn by the transparency path (docs/rendering.md "Transparency").
  addDemoTranslucentSamples(s);
  // Generated pines, plane trees, junipers, boulders and grass scattered
  // over the valley, heather on the big scan (docs/foliage.md).
  if (!addDemoFoliage(s, error)) return std::nullopt;
  // Snow, a fog bank between the pillars and a torch on the tallest (docs/particles.md).
  if (!addDemoParticles(s, error)) return std::nullopt;
  // Bloom and a LUT grade (docs/rendering.md "Post-processing").
  addDemoPost(s);
  // Camera cuts (docs/sequencer.md "Camera cuts"): the stereo flight for
  // 7 s, then a 1 s crossfade to a second rig high on the far side of the
  // bunnies for the last 3 s. Its convergence and height keep the nearest
  // ground in view (about 6 m) inside the comfort budget.
  {
    Entity crane;
    crane.name = "Crane Camera";
    const glm::dvec3 eye(7.0, 9.0, 3.2), target(0.3, 1.2, 0.9);
    crane.transform.translation = eye;
    crane.transform.rotation = sequencer::lookRotation(target - eye);
    crane.camera = Camera{};
    crane.camera->verticalFovDeg = 40.0;
    crane.camera->stereo = Camera::Stereo::OffAxis;
    crane.camera->interaxial = 0.065;
    crane.camera->convergence = 10.0;
    // Its own look over the scene's (docs/rendering.md "Post settings on
    // cameras"): a cooler grade and a vignette, so the crossfade into it
    // combines two differently graded pictures.
    for (const auto& [key, value] : {std::pair<const char*, FieldValue>{"grade.enabled", true},
                                     {"grade.temperature", -0.25}, {"vignette.enabled", true},
                                     {"vignette.intensity", 0.35}})
      findEntityField(std::string("camera.post.") + key)->set(crane, value);
    const EntityId craneId = add(s, crane);
    s.sequence.cuts = {sequencer::CameraCut{s.findByName("Flight Camera"), 0, 419},
                       sequencer::CameraCut{craneId, 420, 599, sequencer::Transition::Crossfade, 60,
                                            sequencer::Ease::InOut}};
  }

  // A huge scan's cluster hierarchy, apart from the valley with its own
  // camera (added last: the cameras and views before it stay as they were).
  addDemoClusterScan(s, *s.assets.at(1).data);

  if (const std::string problem = s.validate(); !problem.empty()) {
    error = "demo scene is inconsistent: " + problem;
    return std::nullopt;
  }
  return s;
}

}  // namespace hs::scene

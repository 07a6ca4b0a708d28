#include <algorithm>
#include <cstdio>

#include "cli/commands.h"
#include "cli/cut_info.h"
#include "cli/material_info.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/terrain_info.h"
#include "cli/time_arg.h"
#include "foliage/manifest.h"
#include "core/json.h"
#include "scene/camera_post.h"
#include "scene/cluster_asset.h"
#include "scene/fields.h"
#include "scene/hscene_file.h"
#include "scene/impostor_key.h"
#include "scene/impostor_ops.h"
#include "scene/mesh_report_text.h"
#include "scene/ocio_config.h"
#include "scene/object_tracks.h"
#include "scene/particle_world.h"
#include "scene/scene_json.h"
#include "scene/world_bounds.h"
#include "sequencer/key_edit.h"

namespace hs::cli {
namespace {

Json arr(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }

std::string componentList(const scene::Entity& e) {
  std::string out;
  for (const auto& c : scene::entityComponents())
    if (c.optional && c.has(e)) out += (out.empty() ? "" : ", ") + c.key;
  return out;
}

// Every level, 0 (the asset's mesh) first: triangles and Hausdorff error in metres.
Json lodsJson(const scene::MeshAsset& a) {
  Json out = Json::array();
  const std::vector<double> errors = a.lodErrors();
  for (size_t k = 0; k < errors.size(); ++k) {
    const mesh::MeshData* m = k == 0 ? a.data.get() : a.lods[k - 1].data.get();
    Json l = Json::object();
    l["level"] = k;
    l["triangles"] = m ? m->triangleCount() : 0;
    l["hausdorff_m"] = errors[k];
    out.push_back(std::move(l));
  }
  return out;
}

// The stored impostor's state ("stored", "stale"), "none" for a mesh a
// foliage type draws with an impostor level that the scene does not store
// (`drawnWithImpostor`: scene::ops::impostorsToBake(state, true)), null
// when the asset has nothing to do with impostors.
const char* impostorWord(const scene::SceneState& s, const scene::MeshAsset& a,
                         const std::vector<scene::AssetId>& drawnWithImpostor) {
  switch (scene::impostorStatus(s, a)) {
    case scene::ImpostorStatus::Stored: return "stored";
    case scene::ImpostorStatus::Stale: return "stale";
    case scene::ImpostorStatus::None: break;
  }
  return std::find(drawnWithImpostor.begin(), drawnWithImpostor.end(), a.id) != drawnWithImpostor.end() ? "none"
                                                                                                        : nullptr;
}

void printLods(const scene::MeshAsset& a) {
  if (a.clusters) {
    const Json c = scene::clusterSummaryJson(*a.clusters);
    std::printf("    Cluster hierarchy: %zu triangles in %zu clusters, %zu levels, %zu pages (%.1f MiB; index %.1f MiB "
                "always in memory, %.1f MiB of pages in memory)\n",
                c["triangles"].get<size_t>(), c["clusters"].get<size_t>(), c["levels"].get<size_t>(),
                c["pages"].get<size_t>(), c["page_bytes"].get<double>() / 1048576.0,
                c["index_bytes"].get<double>() / 1048576.0, c["pages_in_memory_bytes"].get<double>() / 1048576.0);
    std::printf("      per level:");
    for (const Json& l : c["per_level"])
      std::printf(" %zu: %zu clusters, %zu triangles;", l["level"].get<size_t>(), l["clusters"].get<size_t>(),
                  l["triangles"].get<size_t>());
    std::printf("\n");
  }
  if (a.lods.empty()) return;
  std::printf("    LODs: 0: %zu triangles", a.data->triangleCount());
  for (size_t k = 0; k < a.lods.size(); ++k)
    std::printf("; %zu: %zu triangles, hausdorff_m %.4g", k + 1, a.lods[k].data ? a.lods[k].data->triangleCount() : 0,
                a.lods[k].hausdorff);
  std::printf("\n");
}

// Every animated property of every entity: tracks, and a camera path as
// one more (its "path.progress" keys).
size_t trackCount(const sequencer::Sequence& q) {
  size_t n = 0;
  for (const sequencer::Binding& b : q.bindings) n += b.tracks.size() + (b.path ? 1 : 0);
  return n;
}

std::string entityName(const scene::SceneState& s, const sequencer::Binding& b) {
  const std::string name = scene::targetLabel(s, b.entity);
  return name.empty() ? b.label + " [missing]" : name;
}

// Which object a binding animates, under the keys a reader of the JSON
// looks for: entity_id/entity, material_id/material, or settings.
void targetJson(const scene::SceneState& s, const sequencer::Binding& b, Json& t) {
  switch (sequencer::targetKind(b.entity)) {
    case sequencer::TargetKind::Entity:
      t["entity_id"] = b.entity;
      t["entity"] = entityName(s, b);
      break;
    case sequencer::TargetKind::Material:
      t["material_id"] = sequencer::targetMaterial(b.entity);
      t["material"] = entityName(s, b);
      break;
    case sequencer::TargetKind::Settings: t["settings"] = true; break;
  }
}

Json sequenceJson(const scene::SceneState& s) {
  const sequencer::Sequence& q = s.sequence;
  Json o = Json::object();
  o["fps"] = q.rate.fps();
  o["fps_rational"] = std::to_string(q.rate.num) + "/" + std::to_string(q.rate.den);
  o["start_frame"] = q.startFrame;
  o["end_frame"] = q.endFrame;
  o["duration_s"] = double(q.endFrame - q.startFrame + 1) / q.rate.fps();
  return o;
}

Json tracksJson(const scene::SceneState& s) {
  Json out = Json::array();
  for (const sequencer::Binding& b : s.sequence.bindings) {
    auto add = [&](const std::string& property, const std::vector<double>& times, Json t) {
      targetJson(s, b, t);
      t["property"] = property;
      t["keys"] = times.size();
      if (!times.empty()) {
        t["first_key_s"] = times.front();
        t["last_key_s"] = times.back();
      }
      out.push_back(std::move(t));
    };
    if (b.path) {
      std::vector<double> times;
      for (const auto& k : b.path->progress.keys) times.push_back(k.time);
      Json t = Json::object();
      t["path_points"] = b.path->path.points.size();
      add("path.progress", times, std::move(t));
    }
    for (const sequencer::Track& t : b.tracks) {
      const std::string& property = sequencer::trackProperty(t);
      add(property, sequencer::keyTimes(s.sequence, b.entity, property), Json::object());
    }
  }
  return out;
}

void printTracks(const scene::SceneState& s) {
  const sequencer::Sequence& q = s.sequence;
  if (q.bindings.empty()) return;
  std::printf("timeline: %.6g fps, frames %lld-%lld (%.2f s)\n", q.rate.fps(), static_cast<long long>(q.startFrame),
              static_cast<long long>(q.endFrame), double(q.endFrame - q.startFrame + 1) / q.rate.fps());
  for (const Json& t : tracksJson(s)) {
    const size_t keys = t.at("keys").get<size_t>();
    const std::string who = t.contains("entity")     ? t.at("entity").get<std::string>()
                            : t.contains("material") ? "material '" + t.at("material").get<std::string>() + "'"
                                                     : std::string("settings");
    std::printf("  %s  %s: %zu key%s", who.c_str(),
                t.at("property").get<std::string>().c_str(), keys, keys == 1 ? "" : "s");
    if (t.contains("first_key_s"))
      std::printf(" (%.3f..%.3f s)", t.at("first_key_s").get<double>(), t.at("last_key_s").get<double>());
    if (t.contains("path_points")) std::printf(", path through %zu points", t.at("path_points").get<size_t>());
    std::printf("\n");
  }
}

Json particlesJson(const scene::SceneState& s, double time) {
  Json o = Json::object();
  o["time_s"] = time;
  Json list = Json::array();
  for (const scene::EmitterCount& c : scene::liveParticleCounts(s, time)) {
    Json e = Json::object();
    e["entity"] = c.entity;
    e["name"] = c.name;
    e["live"] = c.live;
    e["estimated"] = c.estimated;
    if (!c.error.empty()) e["error"] = c.error;
    e["emitter"] = particles::emitterToJson(s.find(c.entity)->particles->desc);
    list.push_back(std::move(e));
  }
  o["emitters"] = std::move(list);
  return o;
}

// The post settings each camera overrides (scene/camera_post.h), as text:
// {"Crane Camera": {"grade.enabled": "true", "vignette.intensity": "0.35"}}.
Json cameraPostJson(const scene::SceneState& s) {
  Json out = Json::object();
  for (scene::EntityId id : s.cameras()) {
    const scene::Entity& e = *s.find(id);
    if (e.camera->post.empty()) continue;
    Json post = Json::object();
    for (const auto& [key, value] : e.camera->post)
      if (const scene::EntityField* f = scene::findCameraPostField(key))
        post[key] = scene::formatFieldValue(f->type, value, f->enumNames, 6);
    out[e.name] = std::move(post);
  }
  return out;
}

void printCameraPost(const scene::SceneState& s) {
  const Json post = cameraPostJson(s);
  if (post.empty()) return;
  std::printf("camera post settings (over the scene's):\n");
  for (auto it = post.begin(); it != post.end(); ++it) {
    std::string line;
    for (auto kv = it.value().begin(); kv != it.value().end(); ++kv)
      line += (line.empty() ? "" : ", ") + kv.key() + " " + kv.value().get<std::string>();
    std::printf("  %s: %s\n", it.key().c_str(), line.c_str());
  }
}

Json infoJson(const std::string& path, const scene::SceneState& s, double time) {
  Json o = Json::object();
  o["file"] = path;
  o["format_version"] = scene::sceneFileVersion(path);
  Json entities = Json::array();
  for (scene::EntityId id : s.depthFirstOrder()) {
    const scene::Entity& e = *s.find(id);
    Json je = Json::object();
    je["id"] = id;
    je["name"] = e.name;
    je["parent"] = e.parent;
    je["visible"] = e.visible;
    Json comps = Json::array();
    for (const auto& c : scene::entityComponents())
      if (c.optional && c.has(e)) comps.push_back(c.key);
    je["components"] = std::move(comps);
    je["world_position_m"] = arr(glm::dvec3(s.worldMatrix(id)[3]));
    if (e.mesh) je["mesh_asset"] = e.mesh->mesh;
    entities.push_back(std::move(je));
  }
  o["entities"] = std::move(entities);
  Json assets = Json::array();
  const std::vector<scene::AssetId> needImpostor = scene::ops::impostorsToBake(s, true);
  for (const auto& [id, a] : s.assets) {
    Json ja = Json::object();
    ja["id"] = id;
    ja["name"] = a.name;
    ja["source"] = a.sourcePath;
    if (a.data) {
      const mesh::Bounds b = a.data->bounds();
      ja["vertices"] = a.data->vertexCount();
      ja["triangles"] = a.data->triangleCount();
      ja["textures"] = a.data->textures.size();
      ja["materials"] = a.data->materials.size();
      ja["size_m"] = arr(glm::dvec3(b.max - b.min));
      ja["origin"] = arr(a.data->origin);
      ja["lods"] = lodsJson(a);
    }
    ja["clusters"] = a.clusters ? scene::clusterSummaryJson(*a.clusters) : Json(nullptr);
    if (const char* im = impostorWord(s, a, needImpostor)) ja["impostor"] = im;
    if (!a.processReport.is_null()) ja["process_report"] = a.processReport;
    assets.push_back(std::move(ja));
  }
  o["assets"] = std::move(assets);
  o["materials"] = materialsInfoJson(s).at("materials");
  Json cameras = Json::array();
  for (scene::EntityId id : s.cameras()) cameras.push_back(s.find(id)->name);
  o["cameras"] = std::move(cameras);
  o["camera_post"] = cameraPostJson(s);
  o["terrains"] = terrainInfoJson(s);
  o["foliage"] = s.foliage ? foliage::infoJson(s.foliage->store()) : Json(nullptr);
  o["particles"] = particlesJson(s, time);
  o["sequence"] = sequenceJson(s);
  o["cuts"] = cutsJson(s);
  o["tracks"] = tracksJson(s);
  const scene::WorldBox box = scene::worldBounds(s);
  Json bounds = Json::object();
  if (!box.empty) {
    bounds["min"] = arr(box.min);
    bounds["max"] = arr(box.max);
    bounds["size"] = arr(box.size());
  }
  o["bounds_m"] = std::move(bounds);
  o["settings"] = scene::sceneToJson(s).at("settings");
  return o;
}

// Per visible emitter its sprite, rate and live particles at `time`
// (scene/particle_world.h liveParticleCounts).
void printParticlesInfo(const scene::SceneState& s, double time) {
  const std::vector<scene::EmitterCount> counts = scene::liveParticleCounts(s, time);
  if (counts.empty()) return;
  uint64_t total = 0;
  for (const scene::EmitterCount& c : counts) total += c.live;
  std::printf("particles at %.3f s: %llu live in %zu emitter(s)\n", time, static_cast<unsigned long long>(total),
              counts.size());
  for (const scene::EmitterCount& c : counts) {
    const particles::EmitterDesc& d = s.find(c.entity)->particles->desc;
    if (!c.error.empty())
      std::printf("  %s: problem: %s\n", c.name.c_str(), c.error.c_str());
    else
      // A mesh-drawing emitter names its mesh, not the sprite it does not draw.
      std::printf("  %s: %s, %s particles live (rate %g per s, lifetime %g..%g s, max %lld)\n", c.name.c_str(),
                  d.drawMesh.empty()
                      ? (std::string(particles::spriteName(d.sprite)) + " " + particles::blendName(d.blend)).c_str()
                      : ("mesh \"" + d.drawMesh + "\"").c_str(),
                  (c.estimated ? "about " + std::to_string(c.live) : std::to_string(c.live)).c_str(), d.rateAt(time),
                  d.lifetimeMin, d.lifetimeMax, static_cast<long long>(d.maxLive));
  }
}

// Per type its mesh, instance count and memory (foliage/manifest.h infoJson).
void printFoliageInfo(const scene::SceneState& s) {
  if (!s.foliage || s.foliage->empty()) return;
  const Json info = foliage::infoJson(s.foliage->store());
  std::printf("foliage: %zu instances in %zu cells (%.1f MiB)\n", info["instances"].get<size_t>(),
              info["cells"].get<size_t>(), double(info["bytes"].get<size_t>()) / (1024.0 * 1024.0));
  for (const Json& t : info["types"])
    std::printf("  %s: mesh \"%s\", %zu instances\n", t["name"].get<std::string>().c_str(),
                t["mesh"].get<std::string>().c_str(), t["instances"].get<size_t>());
}

void printTree(const scene::SceneState& s, scene::EntityId id, int depth) {
  const scene::Entity& e = *s.find(id);
  const glm::dvec3 p(s.worldMatrix(id)[3]);
  const std::string comps = componentList(e);
  std::printf("  %*s%s%s%s  at %.3f, %.3f, %.3f%s\n", depth * 2, "", e.name.c_str(), comps.empty() ? "" : "  [",
              comps.empty() ? "" : (comps + "]").c_str(), p.x, p.y, p.z, e.visible ? "" : "  (hidden)");
  for (scene::EntityId c : e.children) printTree(s, c, depth + 1);
}

}  // namespace

int runInfo(int argc, char** argv) {
  static const OperationDecl decl{
      .name = "info",
      .summary = "show what a scene holds (--json for JSON)",
      .usage = "<scene.hscene> [--json] [--time SECONDS|FRAMEf]",
      .description = "Lists the scene's entities (hierarchy, components, world positions), mesh assets (triangles, "
                     "vertices, textures, size in metres, origin, LOD levels with their triangles and Hausdorff "
                     "error, the processing summary), cameras, terrains, foliage types with their instance counts, particle emitters with their live particles at --time, "
                     "tracks, and the scene's extent in metres.",
      .positionals = {{.name = "scene.hscene", .help = "the scene file"}},
      .params = {{.key = "json", .option = "json", .label = "JSON", .type = ParamType::Flag,
                  .help = "print it as JSON"},
                 {.key = "time", .option = "time", .label = "Time", .type = ParamType::Text,
                  .help = "scene time the particle counts are for: seconds, or a frame as 150f (default 0)",
                  .valueName = "T"}}};
  OperationArgs args(decl);
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string path = args.positionals()[0];
  std::string error;
  std::optional<scene::SceneState> s = openScene(path, error);
  if (!s) return args.fail(error);
  double time = 0.0;
  if (args.has("time") && !parseTimeArg(args.text("time"), s->sequence.rate, time, error)) return args.usage(error);
  if (args.flag("json")) {
    std::printf("%s\n", writeJson(infoJson(path, *s, time)).c_str());
    return 0;
  }
  std::printf("%s (scene format %d)\n", path.c_str(), scene::sceneFileVersion(path));
  std::printf("entities: %zu  mesh assets: %zu  materials: %zu  textures: %zu  cameras: %zu  terrains: %zu  tracks: %zu\n",
              s->entities.size(), s->assets.size(), s->materials.size(), s->textures.size(), s->cameras().size(),
              scene::terrainEntities(*s, false).size(), trackCount(s->sequence));
  const scene::WorldBox box = scene::worldBounds(*s);
  if (!box.empty) {
    const glm::dvec3 size = box.size();
    std::printf("extent: %.3f x %.3f x %.3f m\n", size.x, size.y, size.z);
  }
  if (!s->sequence.cuts.empty()) printCuts(*s);
  printCameraPost(*s);
  if (const scene::PostSettings& post = s->settings.post; !post.lut.empty())
    std::printf("LUT: %s (%zu bytes, stored in the scene), %s, intensity %g\n", post.lut.fileName.c_str(),
                post.lut.bytes ? post.lut.bytes->size() : size_t(0), post.lutEnabled ? "on" : "off",
                double(post.lutIntensity));
  if (const scene::PostSettings& post = s->settings.post; !post.ocioConfig.empty()) {
    std::string e;
    const scene::DisplayView dv = scene::resolveDisplayView(post.ocioConfig, post.display, post.view, e);
    std::printf("OpenColorIO config: %s (%zu files, stored in the scene), view transform %s, %s\n",
                post.ocioConfig.fileName.c_str(), post.ocioConfig.files.size(), post.viewTransform ? "on" : "off",
                e.empty() ? ("display '" + dv.display + "', view '" + dv.view + "'").c_str() : e.c_str());
  }
  if (!s->assets.empty()) std::printf("mesh assets:\n");
  const std::vector<scene::AssetId> needImpostor = scene::ops::impostorsToBake(*s, true);
  for (const auto& [id, a] : s->assets) {
    if (!a.data) continue;
    const mesh::Bounds b = a.data->bounds();
    const glm::vec3 sz = b.max - b.min;
    std::printf("  %llu %s: %zu triangles, %zu vertices, %zu textures, %.3f x %.3f x %.3f m, origin %.3f, %.3f, %.3f (from %s)\n",
                static_cast<unsigned long long>(id), a.name.c_str(), a.data->triangleCount(), a.data->vertexCount(),
                a.data->textures.size(), double(sz.x), double(sz.y), double(sz.z), a.data->origin.x, a.data->origin.y,
                a.data->origin.z, a.sourcePath.c_str());
    printLods(a);
    if (const char* im = impostorWord(*s, a, needImpostor))
      std::printf("    impostor: %s%s\n", scene::impostorStatusText(scene::impostorStatus(*s, a)).c_str(),
                  std::string(im) == "stored" ? "" : "; `hybridscape-cli foliage impostors` bakes and stores it");
    if (const std::string summary = scene::processReportSummary(a.processReport); !summary.empty())
      std::printf("    processed: %s\n", summary.c_str());
  }
  if (!s->materials.empty()) {
    std::printf("materials (hybridscape-cli material list for their fields):\n");
    const scene::MaterialField& model = *scene::findMaterialField("model");
    for (const auto& [id, m] : s->materials)
      std::printf("  %s  (%s)\n", m.name.c_str(), scene::formatFieldValue(model.type, model.get(m), model.enumNames).c_str());
  }
  printTerrainInfo(*s);
  printFoliageInfo(*s);
  printParticlesInfo(*s, time);
  printTracks(*s);
  std::printf("hierarchy:\n");
  for (scene::EntityId r : s->roots) printTree(*s, r, 0);
  return 0;
}

}  // namespace hs::cli

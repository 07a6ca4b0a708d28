// hybridscape-cli terrain paint-rules
#include <cstdio>
#include <fstream>
#include <sstream>

#include "cli/commands.h"
#include "cli/terrain_cli.h"
#include "core/json.h"
#include "scene/terrain_json.h"
#include "scene/terrain_jobs.h"
#include "scene/terrain_ops.h"

namespace hs::cli {
namespace {

void printRules(const scene::TerrainAsset& t) {
  std::printf("paint rules of '%s' (applied in order; later rules cover earlier ones):\n", t.name.c_str());
  if (t.paintRules.empty()) std::printf("  (none)\n");
  for (size_t i = 0; i < t.paintRules.size(); ++i) {
    const terrain::PaintRule& r = t.paintRules[i];
    const std::string layer = r.layer < int(t.materials.size()) ? t.materials[size_t(r.layer)].name : "?";
    std::printf("  %zu. layer %d (%s), strength %.2f%s", i + 1, r.layer, layer.c_str(), double(r.strength),
                r.enabled ? "" : " (disabled)");
    if (r.useAltitude) std::printf(", altitude %.1f..%.1f m (blend %.1f)", r.altitudeMin, r.altitudeMax, r.altitudeBlend);
    if (r.useSlope) std::printf(", slope %.1f..%.1f deg (blend %.1f)", r.slopeMin, r.slopeMax, r.slopeBlend);
    std::printf("\n");
  }
}

// Rules as the scene description writes them (a JSON array of objects with
// layer, strength, use_altitude, altitude_min/max/blend, use_slope,
// slope_min/max/blend, enabled).
bool readRules(const std::string& file, const scene::TerrainAsset& t, std::vector<terrain::PaintRule>& out,
               std::string& error) {
  std::ifstream in(file);
  if (!in) {
    error = file + ": cannot be read";
    return false;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const std::optional<Json> doc = parseJson(text, error);
  if (!doc) {
    error = file + ": not JSON (" + error + ")";
    return false;
  }
  std::string e;
  JsonReader r(e);
  if (!scene::readPaintRules(r, *doc, "", int(t.materials.size()), out)) {
    error = file + ": paint rules: " + jsonErrorIn(text, r);
    return false;
  }
  return true;
}

}  // namespace

int runTerrainPaintRules(int argc, char** argv) {
  const char* cmd = "terrain paint-rules";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0, {{"terrain"}, {"rules"}, {"defaults", false}, {"show", false}}, args, error))
    return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli terrain paint-rules <scene.hscene> [options]\n\n"
        "Paints a terrain's layers automatically by altitude and slope with its paint\n"
        "rules (one undo step; weights stay summing to 1), and saves the scene.\n\n"
        "  --terrain NAME   which terrain (needed when the scene has several)\n"
        "  --rules FILE     use these rules (a JSON array: layer, strength, enabled,\n"
        "                   use_altitude, altitude_min, altitude_max, altitude_blend,\n"
        "                   use_slope, slope_min, slope_max, slope_blend) and keep them\n"
        "                   as the terrain's rules\n"
        "  --defaults       reset the terrain's rules to the defaults first\n"
        "  --show           print the rules and change nothing\n");
    return 0;
  }
  if (args.positional.size() != 1) return usage(cmd, "expected one scene file");
  if (args.has("rules") && args.has("defaults")) return usage(cmd, "--rules and --defaults exclude each other");
  const std::string path = args.positional[0];
  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return fail(cmd, error);
  const scene::EntityId e = scene::ops::findTerrainEntity(doc.state(), args.get("terrain").value_or(""), error);
  if (e == scene::kNoEntity) return fail(cmd, error);
  const scene::TerrainId id = doc.state().find(e)->terrain->terrain;
  if (args.has("show")) {
    printRules(*doc.state().findTerrain(id));
    return 0;
  }
  if (auto file = args.get("rules")) {
    std::vector<terrain::PaintRule> rules;
    if (!readRules(*file, *doc.state().findTerrain(id), rules, error)) return fail(cmd, error);
    scene::ops::setTerrainPaintRules(doc, id, rules);
  } else if (args.has("defaults")) {
    scene::ops::setTerrainPaintRules(doc, id, scene::defaultPaintRules(doc.state().findTerrain(id)->data->heights()));
  }
  auto job = scene::TerrainJob::paintRules(doc, id);
  if (!job->valid()) return fail(cmd, job->invalidReason());
  Progress progress = terminalProgress("Paint rules");
  job->run(&progress);
  const scene::TerrainJobOutcome out = job->commit(doc);
  for (const auto& w : out.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!out.ok) return fail(cmd, out.error);
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return fail(cmd, error);
  printRules(*doc.state().findTerrain(id));
  std::printf("%s\n%s\n", out.summary.c_str(), saved.c_str());
  return 0;
}

}  // namespace hs::cli

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
#include "terrain/terrain_operations.h"

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
  OperationArgs args(terrain::terrainPaintRulesOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  if (args.has("rules") && args.flag("defaults")) return args.usage("--rules and --defaults exclude each other");
  const std::string path = args.positionals()[0];
  std::string error;
  scene::Document doc;
  const scene::TerrainId id = terrain_cli::openTerrain(path, args.text("terrain"), doc, error);
  if (id == scene::kNoTerrain) return args.fail(error);
  if (args.flag("show")) {
    printRules(*doc.state().findTerrain(id));
    return 0;
  }
  if (args.has("rules")) {
    std::vector<terrain::PaintRule> rules;
    if (!readRules(args.text("rules"), *doc.state().findTerrain(id), rules, error)) return args.fail(error);
    scene::ops::setTerrainPaintRules(doc, id, rules);
  } else if (args.flag("defaults")) {
    scene::ops::setTerrainPaintRules(doc, id, scene::defaultPaintRules(doc.state().findTerrain(id)->data->heights()));
  }
  auto job = scene::TerrainJob::paintRules(doc, id);
  if (!job->valid()) return args.fail(job->invalidReason());
  Progress progress = terminalProgress("Paint rules");
  job->run(&progress);
  const scene::TerrainJobOutcome out = job->commit(doc);
  for (const auto& w : out.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!out.ok) return args.fail(out.error);
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return args.fail(error);
  printRules(*doc.state().findTerrain(id));
  std::printf("%s\n%s\n", out.summary.c_str(), saved.c_str());
  return 0;
}

}  // namespace hs::cli

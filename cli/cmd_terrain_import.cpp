// hybridscape-cli terrain import
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/terrain_cli.h"
#include "scene/terrain_jobs.h"
#include "scene/terrain_ops.h"
#include "terrain/dem_import.h"
#include "terrain/terrain_operations.h"

namespace hs::cli {
int runTerrainImport(int argc, char** argv) {
  OperationArgs args(terrain::terrainImportOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected <dem> <scene.hscene>");
  const std::string dem = args.positionals()[0], path = args.positionals()[1];
  std::string error;
  terrain::DemImportOptions o;
  if (args.has("window") && !terrain::parseDemWindow(args.text("window"), o.window, error)) return args.usage(error);
  if (args.has("samples")) {
    const std::vector<double> n = args.numbers("samples");
    o.samplesX = int(n[0]);
    o.samplesY = int(n[1]);
  }
  const std::string crs = args.text("crs");
  if (crs == "auto") o.crs = terrain::DemCrsMode::Auto;
  else if (crs == "keep") o.crs = terrain::DemCrsMode::KeepSource;
  else if (crs == "local") o.crs = terrain::DemCrsMode::LocalTransverseMercator;
  else if (crs == "utm") o.crs = terrain::DemCrsMode::Utm;
  else if (!crs.empty()) {
    o.crs = terrain::DemCrsMode::Custom;
    o.customCrs = crs;
  } else return args.usage("--crs needs a value");
  const std::string resampling = args.text("resampling");
  o.resampling = resampling == "nearest" ? terrain::Resampling::Nearest
                 : resampling == "cubic" ? terrain::Resampling::Cubic
                                         : terrain::Resampling::Bilinear;
  o.fill = args.text("fill") == "idw" ? terrain::NodataFill::InverseDistance : terrain::NodataFill::Diffusion;
  if (args.has("nodata")) o.nodataValue = args.number("nodata");
  if (args.has("name") && args.text("name").empty()) return args.usage("--name must not be empty");

  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return args.fail(error);
  Progress progress = terminalProgress("Importing " + std::filesystem::path(dem).filename().string());
  std::string line;
  if (args.has("into")) {
    const scene::EntityId e = scene::ops::findTerrainEntity(doc.state(), args.text("into"), error);
    if (e == scene::kNoEntity) return args.fail(error);
    auto job = scene::TerrainJob::demInto(doc, doc.state().find(e)->terrain->terrain, dem, o);
    if (!job->valid()) return args.fail(job->invalidReason());
    job->run(&progress);
    const scene::TerrainJobOutcome out = job->commit(doc);
    for (const auto& w : out.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (!out.ok) return args.fail(out.error);
    line = out.summary;
  } else {
    terrain::DemImportResult r = terrain::importDem(dem, o, &progress);
    for (const auto& w : r.report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (!r.ok()) return args.fail(r.error.empty() ? dem + ": could not be imported" : r.error);
    // Named by the rule the editor's Import DEM uses too (scene/terrain_ops.h).
    std::string name;
    if (scene::ops::addTerrainFromDem(doc, std::move(*r.heightfield), dem, args.text("name"), error, &name) ==
        scene::kNoEntity)
      return args.fail(error);
    line = terrain::summary(r.report) + "\nadded terrain '" + name + "'";
  }
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return args.fail(error);
  std::printf("%s\n%s\n", line.c_str(), saved.c_str());
  return 0;
}

}  // namespace hs::cli

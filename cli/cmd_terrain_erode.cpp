// hybridscape-cli terrain erode
#include <cstdio>

#include "cli/commands.h"
#include "cli/terrain_cli.h"
#include "scene/terrain_jobs.h"
#include "scene/terrain_ops.h"
#include "terrain/terrain_operations.h"

namespace hs::cli {

int runTerrainErode(int argc, char** argv) {
  OperationArgs args(terrain::terrainErodeOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const bool thermal = args.flag("thermal"), hydraulic = args.flag("hydraulic");
  if (thermal == hydraulic) return args.usage("say which erosion: --thermal or --hydraulic");
  const std::string path = args.positionals()[0];
  // Values were checked against the solvers' declarations on parsing.
  terrain::ThermalParams tp;
  terrain::HydraulicParams hp;
  if (args.has("iterations")) tp.iterations = hp.iterations = int(args.integer("iterations"));
  tp.talusDegrees = args.number("talus_deg");
  tp.strength = float(args.number("strength"));
  hp.timeStep = args.number("time_step_s");
  hp.rain = args.number("rain_m_per_s");
  hp.evaporation = args.number("evaporation_per_s");
  hp.sedimentCapacity = args.number("sediment_capacity");
  hp.erosionRate = args.number("erosion_rate_per_s");
  hp.depositionRate = args.number("deposition_rate_per_s");
  const int threads = int(args.integer("threads"));
  const int maskLayer = args.has("mask_layer") ? int(args.integer("mask_layer")) : -1;
  std::string error;

  scene::Document doc;
  const scene::TerrainId id = terrain_cli::openTerrain(path, args.text("terrain"), doc, error);
  if (id == scene::kNoTerrain) return args.fail(error);
  if (maskLayer >= int(doc.state().findTerrain(id)->materials.size()))
    return args.usage("--mask-layer " + std::to_string(maskLayer) + " is not a paint layer of this terrain");
  scene::TerrainJobMask mask;
  mask.paintLayer = maskLayer;
  auto job = thermal ? scene::TerrainJob::thermal(doc, id, tp, mask) : scene::TerrainJob::hydraulic(doc, id, hp, mask);
  if (!job->valid()) return args.fail(job->invalidReason());
  Progress progress = terminalProgress(thermal ? "Thermal erosion" : "Hydraulic erosion");
  job->run(&progress, threads);
  const scene::TerrainJobOutcome out = job->commit(doc);
  for (const auto& w : out.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!out.ok) return args.fail(out.error);
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return args.fail(error);
  if (out.erosion) {
    const terrain::ErosionReport& r = *out.erosion;
    std::printf("mass before %.6g m^3, after %.6g m^3: mass error %.3g m^3 (relative %.3g)\n", r.massBefore, r.massAfter,
                r.massError, r.relativeMassError);
    std::printf("time %.3f s (%.1f M cell-iterations/s on %d threads)\n", r.seconds, r.cellIterationsPerSecond * 1e-6,
                r.threads);
  }
  std::printf("%s\n%s\n", out.summary.c_str(), saved.c_str());
  return 0;
}

}  // namespace hs::cli

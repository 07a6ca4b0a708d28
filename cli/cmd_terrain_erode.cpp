// hybridscape-cli terrain erode
#include <cstdio>

#include "cli/commands.h"
#include "cli/terrain_cli.h"
#include "scene/terrain_jobs.h"
#include "scene/terrain_ops.h"

namespace hs::cli {

int runTerrainErode(int argc, char** argv) {
  const char* cmd = "terrain erode";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0,
                 {{"terrain"}, {"thermal", false}, {"hydraulic", false}, {"iterations"}, {"talus"}, {"strength"},
                  {"rain"}, {"evaporation"}, {"capacity"}, {"erosion-rate"}, {"deposition-rate"}, {"time-step"},
                  {"mask-layer"}, {"threads"}},
                 args, error))
    return usage(cmd, error);
  if (args.help) {
    const terrain::ThermalParams t;
    const terrain::HydraulicParams h;
    std::printf(
        "usage: hybridscape-cli terrain erode <scene.hscene> --thermal|--hydraulic [options]\n\n"
        "Erodes a whole terrain (or where a paint layer is painted) as one undo step,\n"
        "prints the solver's mass error and time, and saves the scene. Out-of-range\n"
        "values are clamped with a warning; the solvers cannot blow up.\n\n"
        "  --terrain NAME        which terrain (needed when the scene has several)\n"
        "  --iterations N        (default thermal %d, hydraulic %d)\n"
        "  --mask-layer N        erode only where paint layer N is painted (weighted)\n"
        "  --threads N           worker threads (default: all)\n"
        "thermal:\n"
        "  --talus DEG           angle of repose, 0..90 (default %.0f)\n"
        "  --strength S          share of the allowed move per iteration, 0..1 (default %.2f)\n"
        "hydraulic (virtual pipes):\n"
        "  --rain M_PER_S        (default %g)      --evaporation PER_S   (default %g)\n"
        "  --capacity KC         (default %g)      --erosion-rate KS     (default %g)\n"
        "  --deposition-rate KD  (default %g)      --time-step S         upper bound (default %g)\n",
        t.iterations, h.iterations, t.talusDegrees, double(t.strength), h.rain, h.evaporation, h.sedimentCapacity,
        h.erosionRate, h.depositionRate, h.timeStep);
    return 0;
  }
  if (args.positional.size() != 1) return usage(cmd, "expected one scene file");
  const bool thermal = args.has("thermal"), hydraulic = args.has("hydraulic");
  if (thermal == hydraulic) return usage(cmd, "say which erosion: --thermal or --hydraulic");
  const std::string path = args.positional[0];
  terrain::ThermalParams tp;
  terrain::HydraulicParams hp;
  int iterations = thermal ? tp.iterations : hp.iterations, threads = 0, maskLayer = -1;
  double strength = double(tp.strength);
  // Ranges here are what a user may type; the solvers clamp further and warn.
  if (!terrain_cli::intOption(args, "iterations", 0, 1000000, iterations, error) ||
      !terrain_cli::intOption(args, "threads", 0, 256, threads, error) ||
      !terrain_cli::intOption(args, "mask-layer", 0, 15, maskLayer, error) ||
      !terrain_cli::doubleOption(args, "talus", -1e9, 1e9, tp.talusDegrees, error) ||
      !terrain_cli::doubleOption(args, "strength", -1e9, 1e9, strength, error) ||
      !terrain_cli::doubleOption(args, "rain", -1e12, 1e12, hp.rain, error) ||
      !terrain_cli::doubleOption(args, "evaporation", -1e12, 1e12, hp.evaporation, error) ||
      !terrain_cli::doubleOption(args, "capacity", -1e12, 1e12, hp.sedimentCapacity, error) ||
      !terrain_cli::doubleOption(args, "erosion-rate", -1e12, 1e12, hp.erosionRate, error) ||
      !terrain_cli::doubleOption(args, "deposition-rate", -1e12, 1e12, hp.depositionRate, error) ||
      !terrain_cli::doubleOption(args, "time-step", -1e12, 1e12, hp.timeStep, error))
    return usage(cmd, error);
  tp.iterations = hp.iterations = iterations;
  tp.strength = float(strength);

  scene::Document doc;
  if (!terrain_cli::openScene(path, doc, error)) return fail(cmd, error);
  const scene::EntityId e = scene::ops::findTerrainEntity(doc.state(), args.get("terrain").value_or(""), error);
  if (e == scene::kNoEntity) return fail(cmd, error);
  const scene::TerrainId id = doc.state().find(e)->terrain->terrain;
  if (maskLayer >= int(doc.state().findTerrain(id)->materials.size()))
    return usage(cmd, "--mask-layer " + std::to_string(maskLayer) + " is not a paint layer of this terrain");
  scene::TerrainJobMask mask;
  mask.paintLayer = maskLayer;
  auto job = thermal ? scene::TerrainJob::thermal(doc, id, tp, mask) : scene::TerrainJob::hydraulic(doc, id, hp, mask);
  if (!job->valid()) return fail(cmd, job->invalidReason());
  Progress progress = terminalProgress(thermal ? "Thermal erosion" : "Hydraulic erosion");
  job->run(&progress, threads);
  const scene::TerrainJobOutcome out = job->commit(doc);
  for (const auto& w : out.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  if (!out.ok) return fail(cmd, out.error);
  std::string saved;
  if (!terrain_cli::saveScene(doc, path, error, saved)) return fail(cmd, error);
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

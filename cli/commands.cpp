#include "cli/commands.h"

#include <cstdio>
#include <unistd.h>

#include "scene/hscene_repair.h"
#include "scene/import_pipeline.h"
#include "scene/render_operation.h"
#include "sequencer/sequencer_operations.h"

namespace hs::cli {

const std::vector<Command>& commands() {
  // The shared operations' summaries are their declarations'.
  static const std::vector<Command> list = {
      {"new", "create a scene with a sun and a camera", runNew},
      {"demo", "write the built-in demo scene", runDemo},
      {"import", scene::meshImportOperation().summary.c_str(), runImport},
      {"info", "show what a scene holds (--json for JSON)", runInfo},
      {"render", scene::renderOperation().summary.c_str(), runRender},
      {"set", "set an entity property or a scene setting", runSet},
      {"material", "materials: list (--json), set <material> <field> <value>", runMaterial},
      {"terrain", "terrains: new, import (DEM), erode, paint-rules, export", runTerrain},
      {"foliage", "foliage: plant (generate), type add, scatter, clear", runFoliage},
      {"particles", "particle emitters: add a preset (snow, fog, torch, campfire, dust)", runParticles},
      {"mesh", "meshes: export (OBJ, PLY, GLB, 3D Tiles)", runMesh},
      {"light", "lights: add a sun, point or spot light", runLight},
      {"lut", "the grading LUT: import (OpenColorIO formats, stored in the scene), clear", runLut},
      {"ocio", "the OpenColorIO config and its view transform: import (stored in the scene), list, clear", runOcio},
      {"key", sequencer::keyOperation().summary.c_str(), runKey},
      {"cut", "camera cuts: add (with a transition), list, remove", runCut},
      {"sequence", sequencer::sequenceOperation().summary.c_str(), runSequence},
      {"path", sequencer::pathOperation().summary.c_str(), runPath},
      {"farm", "render-farm runs: write/submit a Slurm job array, verify frames", runFarm},
      {"repair", scene::repairOperation().summary.c_str(), runRepair},
  };
  return list;
}

Progress terminalProgress(const std::string& label) {
  if (!isatty(STDERR_FILENO)) return Progress();
  return Progress([label, last = -1](double f, std::string_view stage) mutable {
    const int pct = int(f * 100.0);
    if (pct == last) return;
    last = pct;
    std::fprintf(stderr, "\r%s: %-20.*s %3d%%%s", label.c_str(), int(stage.size()), stage.data(), pct,
                 pct >= 100 ? "\n" : "");
    std::fflush(stderr);
  });
}

}  // namespace hs::cli

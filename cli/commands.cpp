#include "cli/commands.h"

#include <cstdio>
#include <unistd.h>

namespace hs::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"new", "create a scene with a sun and a camera", runNew},
      {"demo", "write the built-in demo scene", runDemo},
      {"import", "import a mesh (OBJ, FBX, PLY, glTF, ...) into a scene", runImport},
      {"info", "show what a scene holds (--json for JSON)", runInfo},
      {"render", "render a frame or a stereo frame sequence headless (PNG, EXR, JPEG, TIFF, MP4)", runRender},
      {"set", "set an entity property or a scene setting", runSet},
      {"terrain", "terrains: new, import (DEM), erode, paint-rules, export", runTerrain},
      {"key", "set a key on the timeline (an entity property at a time)", runKey},
      {"sequence", "show or set the timeline's frame rate and range", runSequence},
      {"path", "make a camera follow a path at constant speed (look-at or banking), edit or clear it", runPath},
      {"farm", "render-farm runs: write/submit a Slurm job array, verify frames", runFarm},
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

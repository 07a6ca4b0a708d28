// `hybridscape-cli repair DAMAGED OUT`: the command line of
// scene::repairScene (hscene_repair.h).
#include <cstdio>

#include "cli/commands.h"
#include "cli/operation_options.h"
#include "scene/hscene_repair.h"

namespace hs::cli {

int runRepair(int argc, char** argv) {
  OperationArgs args(scene::repairOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 2) return args.usage("expected the damaged scene and a new file name");
  const std::string damaged = args.positionals()[0], out = args.positionals()[1];
  scene::RepairReport r;
  std::string error;
  if (!scene::repairScene(damaged, out, r, error)) return args.fail(error);
  for (const std::string& n : r.notes) std::printf("note: %s\n", n.c_str());
  for (const std::string& d : r.dropped) std::printf("dropped: %s\n", d.c_str());
  std::printf("wrote %s (%zu entities, %zu meshes, %zu terrains; %s) from %s, which is unchanged\n", out.c_str(),
              r.entities, r.meshes, r.terrains,
              r.wasWhole ? "it opened as it was: nothing was lost"
                         : (std::to_string(r.dropped.size()) + " thing(s) dropped").c_str(),
              damaged.c_str());
  return 0;
}

}  // namespace hs::cli

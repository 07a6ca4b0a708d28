#pragma once
// The subcommands of hybridscape-cli. Each takes argv after the subcommand
// name and returns the process exit code (0 ok, 1 failure, 2 usage).
#include <string>
#include <vector>

#include "core/progress.h"

namespace hs::cli {

struct Command {
  const char* name;
  const char* summary;
  int (*run)(int argc, char** argv);
};

const std::vector<Command>& commands();

int runNew(int argc, char** argv);
int runDemo(int argc, char** argv);
int runImport(int argc, char** argv);
int runInfo(int argc, char** argv);
int runRender(int argc, char** argv);
int runSet(int argc, char** argv);
int runMaterial(int argc, char** argv);
int runTerrain(int argc, char** argv);
int runFoliage(int argc, char** argv);
int runFoliageImpostors(int argc, char** argv);  // `foliage impostors` (cmd_foliage_impostors.cpp)
int runParticles(int argc, char** argv);
int runMesh(int argc, char** argv);
int runLight(int argc, char** argv);
int runLut(int argc, char** argv);
int runOcio(int argc, char** argv);
int runCut(int argc, char** argv);
int runKey(int argc, char** argv);
int runSequence(int argc, char** argv);
int runPath(int argc, char** argv);
int runFarm(int argc, char** argv);
int runRepair(int argc, char** argv);

// A progress line on stderr when it is a terminal ("Importing bunny.obj  42%").
Progress terminalProgress(const std::string& label);

}  // namespace hs::cli

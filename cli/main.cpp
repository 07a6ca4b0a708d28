// hybridscape-cli: scripts imports, edits and headless renders of .hscene
// scenes through the same command API and renderer as the editor.
#include <QCoreApplication>
#include <cstdio>
#include <cstring>

#include "cli/commands.h"

namespace {

void printHelp() {
  std::printf(
      "hybridscape-cli - script Hybridscape scenes from the command line\n\n"
      "usage: hybridscape-cli <command> [arguments] [--help]\n\n"
      "commands:\n");
  for (const auto& c : hs::cli::commands()) std::printf("  %-8s %s\n", c.name, c.summary);
  std::printf(
      "\nA command that changes a scene takes the scene file last.\n"
      "Exit status: 0 on success, 1 when the command fails, 2 for bad usage.\n");
}

}  // namespace

int main(int argc, char** argv) {
  // Qt's core (JSON, undo stack, resources) without any GUI or display.
  QCoreApplication app(argc, argv);
  QCoreApplication::setApplicationName("hybridscape-cli");
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    printHelp();
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::printf("hybridscape-cli 0.1.0\n");
    return 0;
  }
  for (const auto& c : hs::cli::commands())
    if (!std::strcmp(argv[1], c.name)) return c.run(argc - 2, argv + 2);
  std::fprintf(stderr, "hybridscape-cli: error: unknown command '%s' (see hybridscape-cli --help)\n", argv[1]);
  return 2;
}

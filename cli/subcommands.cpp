#include "cli/subcommands.h"

#include <cstdio>
#include <cstring>

namespace hs::cli {

int runSubcommands(const char* group, const std::string& about, std::span<const Subcommand> subs, int argc,
                   char** argv) {
  if (argc < 1 || !std::strcmp(argv[0], "--help") || !std::strcmp(argv[0], "-h")) {
    std::printf("usage: hybridscape-cli %s <subcommand> [arguments] [--help]\n\n%s%ssubcommands:\n", group,
                about.c_str(), about.empty() ? "" : "\n");
    for (const Subcommand& s : subs) std::printf("  %-12s %s\n", s.name, s.decl().summary.c_str());
    return argc < 1 ? 2 : 0;
  }
  for (const Subcommand& s : subs)
    if (!std::strcmp(argv[0], s.name)) return s.run(argc - 1, argv + 1);
  std::fprintf(stderr, "hybridscape-cli %s: error: unknown subcommand '%s' (see hybridscape-cli %s --help)\n", group,
               argv[0], group);
  return 2;
}

}  // namespace hs::cli

#pragma once
// Commands made of subcommands (`terrain new|import|...`, `mesh export`):
// one dispatcher, so their --help listing, the exit codes and the message
// for an unknown subcommand are the same for every group.
#include <span>
#include <string>

#include "core/params.h"

namespace hs::cli {

struct Subcommand {
  const char* name;
  const OperationDecl& (*decl)();  // its summary, for the listing
  int (*run)(int argc, char** argv);
};

// Runs the subcommand argv[0] names with the arguments after it. With no
// arguments: the listing on stdout and exit 2; with --help or -h: the
// listing and 0; an unknown name: one line on stderr and 2. `about`, when
// not empty, is printed between the usage line and the listing.
int runSubcommands(const char* group, const std::string& about, std::span<const Subcommand> subs, int argc,
                   char** argv);

}  // namespace hs::cli

#pragma once
// A scratch name (core/scratch_files.h) as a process of this machine that
// has ended would have made it: what a killed build or save leaves behind,
// for tests of the sweep. The process is a child forked and reaped here,
// so its id is certainly no longer running.
#include <sys/wait.h>
#include <unistd.h>

#include <string>

namespace hs::test {

struct DeadScratch {
  std::string name;  // empty: no child could be forked
  long pid = 0;      // the ended process
};

// `live`: a name scratchName made in this process.
inline DeadScratch asDeadProcess(const std::string& live) {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  if (child <= 0 || ::waitpid(child, nullptr, 0) != child) return {};
  const std::string mine = "-" + std::to_string(::getpid()) + "-";
  const size_t at = live.rfind(mine);
  if (at == std::string::npos) return {};
  DeadScratch d{live, long(child)};
  d.name.replace(at, mine.size(), "-" + std::to_string(child) + "-");
  return d;
}

}  // namespace hs::test

#pragma once
// Starting helper programs (ffmpeg for films, the mesh import worker) with
// posix_spawn, the one copy for every library. posix_spawn rather than
// fork+exec: it does not copy the page tables of an editor holding gigabytes
// of scan data, and it is safe to call from any thread.
#include <sys/types.h>

#include <string>
#include <utility>
#include <vector>

namespace hs {

struct SpawnOptions {
  std::vector<std::string> args;  // args[0] is the program
  bool searchPath = false;        // look args[0] up in PATH (posix_spawnp)
  // Child descriptors: {child fd, parent fd}, dup2'ed in order; a parent fd
  // of -1 opens /dev/null there instead.
  std::vector<std::pair<int, int>> fds;
  int closeFrom = -1;  // closes every child fd >= this (glibc 2.34+), -1 = keep
  // Default signal dispositions and an empty mask in the child (a parent
  // that ignores SIGPIPE or blocks SIGINT must not pass that on).
  bool resetSignals = true;
  // "NAME=value" entries added to (or replacing) the parent's environment.
  std::vector<std::string> environment;
};

// The child's pid, or -1 with `error` ("cannot start ffmpeg: No such file
// or directory"; `hint` is appended when the program is missing).
pid_t spawnProcess(const SpawnOptions& options, std::string& error, const std::string& missingHint = {});

// Waits for `pid` (restarting on EINTR). The exit code, or 128 + signal for
// a child killed by a signal, or -1 if it could not be waited for. `status`
// gets the raw wait status when given.
int waitProcess(pid_t pid, int* status = nullptr);

}  // namespace hs

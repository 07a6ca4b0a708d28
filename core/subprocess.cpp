#include "core/subprocess.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>

extern char** environ;

namespace hs {

pid_t spawnProcess(const SpawnOptions& o, std::string& error, const std::string& missingHint) {
  if (o.args.empty()) {
    error = "cannot start a process: no program given";
    return -1;
  }
  std::vector<char*> argv;
  for (const std::string& a : o.args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  // The environment: the parent's, with o.environment's names replaced.
  std::vector<std::string> added = o.environment;
  std::vector<char*> envp;
  for (char** e = environ; e && *e; ++e) {
    bool replaced = false;
    for (const std::string& a : added) {
      const size_t eq = a.find('=');
      if (eq != std::string::npos && std::strncmp(*e, a.c_str(), eq + 1) == 0) replaced = true;
    }
    if (!replaced) envp.push_back(*e);
  }
  for (std::string& a : added) envp.push_back(a.data());
  envp.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  for (const auto& [child, parent] : o.fds) {
    if (parent < 0) posix_spawn_file_actions_addopen(&actions, child, "/dev/null", O_RDWR, 0);
    else posix_spawn_file_actions_adddup2(&actions, parent, child);
  }
#if defined(__GLIBC__) && __GLIBC_PREREQ(2, 34)
  if (o.closeFrom >= 0) posix_spawn_file_actions_addclosefrom_np(&actions, o.closeFrom);
#endif
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  if (o.resetSignals) {
    sigset_t none, all;
    sigemptyset(&none);
    sigfillset(&all);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setsigdefault(&attr, &all);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  }
  pid_t pid = -1;
  const int rc = o.searchPath ? ::posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), envp.data())
                              : ::posix_spawn(&pid, argv[0], &actions, &attr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    error = "cannot start " + o.args[0] + ": " + std::strerror(rc) + (rc == ENOENT ? missingHint : std::string());
    return -1;
  }
  return pid;
}

int waitProcess(pid_t pid, int* status) {
  int s = 0;
  while (::waitpid(pid, &s, 0) < 0)
    if (errno != EINTR) return -1;
  if (status) *status = s;
  return WIFEXITED(s) ? WEXITSTATUS(s) : 128 + (WIFSIGNALED(s) ? WTERMSIG(s) : 0);
}

}  // namespace hs

#include "scene/import_isolation.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "core/parallel.h"
#include "core/subprocess.h"
#include "mesh/import_wire.h"

namespace hs::scene {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kWorkerName = "hybridscape-import-worker";

// What users call the format: "FBX", "glTF", "PLY", ...
std::string formatName(const std::string& path) {
  const std::string e = mesh::lowerExtension(path);
  if (e == ".gltf" || e == ".glb") return "glTF";
  if (e == ".dae") return "COLLADA";
  std::string n = e.empty() ? std::string("mesh") : e.substr(1);
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return n;
}

std::string signalName(int sig) {
#if defined(__GLIBC__) && __GLIBC_PREREQ(2, 32)
  if (const char* abbrev = sigabbrev_np(sig)) return std::string("SIG") + abbrev;
#endif
  return "signal " + std::to_string(sig);
}

bool isExecutable(const std::string& path) {
  struct stat st {};
  return !path.empty() && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// Moves `fd` to a number of at least 10 (close-on-exec), so that handing it
// to the child as 0..3 never meets the same number.
int highFd(int fd) {
  if (fd < 0) return fd;
  const int high = ::fcntl(fd, F_DUPFD_CLOEXEC, 10);
  ::close(fd);
  return high;
}

// An anonymous temporary file (gone when the last descriptor closes, even if
// this process dies).
int anonymousTempFile() {
  const char* env = std::getenv("TMPDIR");
  const std::string dir = env && *env ? env : "/tmp";
#ifdef O_TMPFILE
  int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd >= 0) return highFd(fd);
#endif
  std::string templ = dir + "/hybridscape-import-XXXXXX";
  int fd2 = ::mkostemp(templ.data(), O_CLOEXEC);
  if (fd2 < 0) return -1;
  ::unlink(templ.c_str());
  return highFd(fd2);
}

// The last 4 kB the worker wrote to stderr.
std::string stderrTail(int fd) {
  if (fd < 0) return {};
  const off_t size = ::lseek(fd, 0, SEEK_END);
  if (size <= 0) return {};
  const off_t from = std::max<off_t>(0, size - 4096);
  std::string text(size_t(size - from), '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), from);
  text.resize(n > 0 ? size_t(n) : 0);
  return text;
}

// The last non-empty line the worker wrote to stderr (at most 200 characters).
std::string lastLine(int fd) {
  std::string text = stderrTail(fd);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  const size_t nl = text.find_last_of('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  if (line.size() > 200) line = line.substr(0, 200) + "...";
  return line;
}

struct Fds {
  int result = -1, err = -1, progressRead = -1, progressWrite = -1, stdinRead = -1, stdinWrite = -1;
  ~Fds() {
    for (int fd : {result, err, progressRead, progressWrite, stdinRead, stdinWrite})
      if (fd >= 0) ::close(fd);
  }
  static void closeOne(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

bool makePipe(int& readEnd, int& writeEnd) {
  int p[2];
  if (::pipe2(p, O_CLOEXEC) != 0) return false;
  readEnd = highFd(p[0]);
  writeEnd = highFd(p[1]);
  return readEnd >= 0 && writeEnd >= 0;
}

std::string mib(uint64_t bytes) { return std::to_string((bytes + (1 << 19)) >> 20) + " MiB"; }

enum class Outcome { Done, SpawnFailed };

Outcome runWorker(const std::string& worker, const std::string& path, const mesh::ImportOptions& options,
                  const WorkerLimits& limits, const Progress* progress, mesh::ImportResult& out,
                  std::string& spawnError) {
  const auto start = Clock::now();
  auto failed = [&](std::string error) {
    out = {};
    out.report.file = path;
    out.report.reader = "assimp";
    out.error = std::move(error);
    return Outcome::Done;
  };

  Fds fds;
  fds.result = anonymousTempFile();
  fds.err = anonymousTempFile();
  if (fds.result < 0 || fds.err < 0 || !makePipe(fds.progressRead, fds.progressWrite) ||
      !makePipe(fds.stdinRead, fds.stdinWrite)) {
    spawnError = std::string("cannot make the worker's files: ") + std::strerror(errno);
    return Outcome::SpawnFailed;
  }

  std::vector<std::string> args = {worker, "--result-fd", "3", "--watch-stdin"};
  if (limits.memoryBytes) {
    args.push_back("--memory-limit-mb");
    args.push_back(std::to_string(limits.memoryBytes >> 20));
  }
  for (auto& a : mesh::importWorkerArguments(path, options)) args.push_back(std::move(a));
  SpawnOptions spawn;
  spawn.args = std::move(args);
  spawn.fds = {{0, fds.stdinRead}, {1, fds.progressWrite}, {2, fds.err}, {3, fds.result}};
  spawn.closeFrom = 4;
  // glibc's fatal messages ("double free detected") go to stderr, not the tty.
  spawn.environment = {"LIBC_FATAL_STDERR_=1"};
  const pid_t pid = spawnProcess(spawn, spawnError);
  if (pid < 0) return Outcome::SpawnFailed;
  Fds::closeOne(fds.stdinRead);
  Fds::closeOne(fds.progressWrite);

  // Progress lines until the worker closes its stdout (it ended). Cancel is
  // polled all the while: the worker is killed, not asked.
  double lastFraction = 0.0;
  std::string lastStage = "Reading with Assimp";
  reportProgress(progress, 0.0, lastStage);
  std::string buffer;
  char chunk[4096];
  auto cancelled = [&] {
    ::kill(pid, SIGKILL);
    waitProcess(pid);
    out = {};
    out.report.file = path;
    out.report.reader = "assimp";
    out.cancelled = true;
    out.error = path + ": import cancelled";
    return Outcome::Done;
  };
  // The watchdog: progress that stops changing for this long means a
  // reader that spins (Assimp 5.2.5 on some damaged files) or waits.
  auto lastChange = Clock::now();
  auto stuck = [&] {
    ::kill(pid, SIGKILL);
    waitProcess(pid);
    char secs[32];
    std::snprintf(secs, sizeof secs, "%g", limits.watchdogSeconds);
    return failed(path + ": the " + formatName(path) + " reader (Assimp) made no progress for " + secs +
                  " s (stuck at " + std::to_string(int(lastFraction * 100.0)) + "%, '" + lastStage +
                  "'), so the import watchdog stopped it; the file is probably damaged (HS_IMPORT_WATCHDOG_S "
                  "sets the time). Nothing was imported.");
  };
  for (;;) {
    if (isCancelled(progress)) return cancelled();
    if (limits.watchdogSeconds > 0 &&
        std::chrono::duration<double>(Clock::now() - lastChange).count() > limits.watchdogSeconds)
      return stuck();
    pollfd p{fds.progressRead, POLLIN, 0};
    const int n = ::poll(&p, 1, 50);
    if (n < 0 && errno != EINTR) break;
    if (n > 0) {
      const ssize_t got = ::read(fds.progressRead, chunk, sizeof chunk);
      if (got < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (got <= 0) break;  // end: the worker is gone
      buffer.append(chunk, size_t(got));
      size_t nl;
      while ((nl = buffer.find('\n')) != std::string::npos) {
        double f;
        std::string stage;
        if (mesh::parseImportProgressLine(std::string_view(buffer).substr(0, nl), f, stage)) {
          if (std::clamp(f, 0.0, 1.0) != lastFraction || stage != lastStage) lastChange = Clock::now();
          lastFraction = std::clamp(f, 0.0, 1.0);
          lastStage = std::move(stage);
          reportProgress(progress, lastFraction, lastStage);
        }
        buffer.erase(0, nl + 1);
      }
    }
  }
  // Its stdout is closed, so it is ending; Cancel still holds while it does.
  int status = 0;
  bool reaped = false;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) {
      reaped = true;
      break;
    }
    if (w < 0 && errno != EINTR) break;  // ECHILD: someone else reaped it (SIGCHLD ignored); the result tells
    if (isCancelled(progress)) return cancelled();
    if (w == 0) ::poll(nullptr, 0, 5);
  }

  const std::string reader = "the " + formatName(path) + " reader (Assimp)";
  // A reader that cannot allocate under the limit may abort instead of
  // failing cleanly; the worker said so on stderr (tools/import_worker).
  const std::string memory =
      limits.memoryBytes ? " (The import worker's memory limit was " + mib(limits.memoryBytes) + ", " +
                               limits.memoryText + "; HS_IMPORT_MEMORY_LIMIT sets it.)"
                         : std::string();
  if (reaped && WIFSIGNALED(status) && limits.memoryBytes &&
      stderrTail(fds.err).find("out of memory: an allocation failed under the memory limit") != std::string::npos)
    return failed(path + ": " + reader + " ran out of memory: it reached the import worker's memory limit of " +
                  mib(limits.memoryBytes) + " (" + limits.memoryText + "; HS_IMPORT_MEMORY_LIMIT sets it) and stopped (" +
                  signalName(WTERMSIG(status)) + "). Nothing was imported.");
  if (reaped && WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    if (sig == SIGKILL)
      return failed(path + ": " + reader + " was killed (SIGKILL) while reading this file, perhaps for using too much memory. Nothing was imported." + memory);
    return failed(path + ": " + reader + " crashed on this file (" + signalName(sig) +
                  "); it is probably damaged. Nothing was imported." + memory);
  }
  const int code = reaped && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::string readError;
  mesh::ImportResult r;
  bool haveResult = false;
  if (code == 0 || !reaped) {
    const int dupFd = ::dup(fds.result);
    if (std::FILE* in = dupFd >= 0 ? ::fdopen(dupFd, "rb") : nullptr) {
      haveResult = mesh::readImportResult(in, r, readError);
      std::fclose(in);
    } else {
      if (dupFd >= 0) ::close(dupFd);
      readError = std::strerror(errno);
    }
  }
  if (!haveResult) {
    std::string why = code >= 0 ? "exit code " + std::to_string(code) : std::string("its exit status is unknown");
    const std::string said = lastLine(fds.err);
    if (!said.empty()) why += ": " + said;
    else if (!readError.empty()) why += ": " + readError;
    return failed(path + ": " + reader + " stopped without a result (" + why + "). Nothing was imported.");
  }
  r.report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  // The worker names the file and the stage; the limit is ours to name.
  if (!r.ok() && limits.memoryBytes && r.error.find("ran out of memory") != std::string::npos)
    r.error += " (the import worker's memory limit: " + mib(limits.memoryBytes) + ", " + limits.memoryText +
               "; HS_IMPORT_MEMORY_LIMIT sets it)";
  out = std::move(r);
  return Outcome::Done;
}

}  // namespace

bool readsWithAssimp(const std::string& path, const mesh::ImportOptions& options) {
  if (options.reader == mesh::Reader::Obj) return false;
  if (options.reader == mesh::Reader::Assimp) return true;
  // Our own readers (OBJ, PLY) run in-process: no start-up to pay.
  const std::string ext = mesh::lowerExtension(path);
  return ext != ".obj" && ext != ".ply";
}

std::string findImportWorker(std::string* lookedAt) {
  std::vector<std::string> tried;
  auto found = [&](const std::string& p) {
    tried.push_back(p);
    return isExecutable(p);
  };
  std::string result;
  if (const char* env = std::getenv("HS_IMPORT_WORKER"); env && *env) {
    if (found(env)) result = env;
  } else {
#ifdef HS_IMPORT_WORKER_PATH
    if (found(HS_IMPORT_WORKER_PATH)) result = HS_IMPORT_WORKER_PATH;
#endif
    if (result.empty()) {
      std::error_code ec;
      const fs::path self = fs::read_symlink("/proc/self/exe", ec);
      if (!ec) {
        const std::string beside = (self.parent_path() / kWorkerName).string();
        if (found(beside)) result = beside;
      }
    }
  }
  if (lookedAt) {
    lookedAt->clear();
    for (const auto& t : tried) *lookedAt += (lookedAt->empty() ? "" : ", ") + t;
  }
  return result;
}

bool workerLimits(WorkerLimits& limits, std::string& error) {
  limits = {};
  const char* memory = std::getenv("HS_IMPORT_MEMORY_LIMIT");
  std::string text = memory && *memory ? memory : "50%";
  const double physical = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  const bool percent = end && *end == '%' && end[1] == '\0';
  if (!end || end == text.c_str() || !(percent || *end == '\0') || !(value >= 0.0) ||
      (percent ? value > 100.0 : value > 1e9)) {
    error = "HS_IMPORT_MEMORY_LIMIT: '" + text + "' is not a memory limit (a share such as 50%, a number of MiB, "
            "or 0 for none)";
    return false;
  }
  if (value > 0.0) {
    // At least 64 MiB: the worker's own libraries take tens of MiB.
    limits.memoryBytes = uint64_t(std::max(percent ? physical * value / 100.0 : value * 1048576.0, 67108864.0));
    char what[96];
    if (percent) std::snprintf(what, sizeof what, "%s of %.1f GiB", text.c_str(), physical / 1073741824.0);
    else std::snprintf(what, sizeof what, "set to %s MiB", text.c_str());
    limits.memoryText = what;
  }
  const char* watchdog = std::getenv("HS_IMPORT_WATCHDOG_S");
  text = watchdog && *watchdog ? watchdog : "300";
  limits.watchdogSeconds = std::strtod(text.c_str(), &end);
  if (!end || end == text.c_str() || *end != '\0' || !(limits.watchdogSeconds >= 0.0) ||
      limits.watchdogSeconds > 1e7) {
    error = "HS_IMPORT_WATCHDOG_S: '" + text + "' is not a number of seconds (0 for no watchdog)";
    return false;
  }
  return true;
}

unsigned tileReadParallelism(const std::vector<std::string>& paths, const mesh::ImportOptions& options) {
  const bool anyWorker = std::any_of(paths.begin(), paths.end(),
                                     [&](const std::string& p) { return readsWithAssimp(p, options); });
  if (!anyWorker) return 1;
  unsigned n = hardwareThreads();
  WorkerLimits limits;
  std::string ignored;  // a bad setting is reported by the tile's own read
  if (workerLimits(limits, ignored) && limits.memoryBytes > 0) {
    const double physical = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
    n = std::min(n, unsigned(std::max(1.0, std::floor(physical / double(limits.memoryBytes)))));
  }
  return std::max(1u, std::min<unsigned>(n, unsigned(paths.size())));
}

mesh::ImportResult importMeshIsolated(const std::string& path, const mesh::ImportOptions& options,
                                      const Progress* progress) {
  if (!readsWithAssimp(path, options)) return mesh::importMesh(path, options, progress);
  std::string lookedAt, why;
  WorkerLimits limits;
  if (!workerLimits(limits, why)) {
    mesh::ImportResult r;
    r.report.file = path;
    r.report.reader = "assimp";
    r.error = path + ": not read: " + why;
    return r;
  }
  const std::string worker = findImportWorker(&lookedAt);
  if (!worker.empty()) {
    mesh::ImportResult r;
    if (runWorker(worker, path, options, limits, progress, r, why) == Outcome::Done) return r;
  } else {
    why = std::string(kWorkerName) + " not found" + (lookedAt.empty() ? "" : " (looked at " + lookedAt + ")");
  }
  mesh::ImportResult r = mesh::importMesh(path, options, progress);
  r.report.warnings.push_back(path + ": read inside this process, not in the import worker (" + why +
                              "); a reader crash on a damaged file would end the program");
  return r;
}

}  // namespace hs::scene

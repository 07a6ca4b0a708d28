#include "scene/import_isolation.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
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
#include <memory>
#include <mutex>
#include <string_view>

#include "core/memory_limit.h"
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

// Kills `pid` and waits for it.
void killAndReap(pid_t pid) {
  ::kill(pid, SIGKILL);
  waitProcess(pid);
}

// One worker process in --serve mode (tools/import_worker), kept for the
// files of one import: the request goes to its stdin, progress lines and a
// "done" line come on its stdout, the result in an anonymous file it
// rewrites for each request. A worker that crashes, hangs or is cancelled
// is killed and reaped; the pool then starts another for the next file.
class WorkerProcess {
 public:
  WorkerProcess() = default;
  WorkerProcess(const WorkerProcess&) = delete;
  WorkerProcess& operator=(const WorkerProcess&) = delete;
  ~WorkerProcess() { stop(); }

  // False with `error` when it could not be started.
  bool start(const std::string& worker, const WorkerLimits& limits, std::string& error) {
    limits_ = limits;
    fds_.result = anonymousTempFile();
    fds_.err = anonymousTempFile();
    // The request channel is a socket, not a pipe: a send to a worker that
    // died is an error (MSG_NOSIGNAL), not a SIGPIPE for this process.
    int sv[2] = {-1, -1};
    if (fds_.result < 0 || fds_.err < 0 || !makePipe(fds_.progressRead, fds_.progressWrite) ||
        ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
      error = std::string("cannot make the worker's files: ") + std::strerror(errno);
      return false;
    }
    fds_.stdinRead = highFd(sv[0]);
    fds_.stdinWrite = highFd(sv[1]);
    std::vector<std::string> args = {worker, "--result-fd", "3", "--serve"};
    if (limits.memoryBytes) {
      args.push_back("--memory-limit-mb");
      args.push_back(std::to_string(limits.memoryBytes >> 20));
    }
    SpawnOptions spawn;
    spawn.args = std::move(args);
    spawn.fds = {{0, fds_.stdinRead}, {1, fds_.progressWrite}, {2, fds_.err}, {3, fds_.result}};
    spawn.closeFrom = 4;
    // glibc's fatal messages ("double free detected") go to stderr, not the tty.
    spawn.environment = {"LIBC_FATAL_STDERR_=1"};
    pid_ = spawnProcess(spawn, error);
    Fds::closeOne(fds_.stdinRead);
    Fds::closeOne(fds_.progressWrite);
    return pid_ > 0;
  }

  bool running() const { return pid_ > 0; }

  // Reads `path`. `since` is when the caller started on it (the report's
  // time includes starting the worker when this read needed one).
  mesh::ImportResult read(const std::string& path, const mesh::ImportOptions& options, const Progress* progress,
                          Clock::time_point since) {
    path_ = &path;
    const std::string request = mesh::importRequest(mesh::importWorkerArguments(path, options));
    for (size_t sent = 0; sent < request.size();) {
      const ssize_t n = ::send(fds_.stdinWrite, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return ended(progress);  // it died before this file: say how
      sent += size_t(n);
    }
    // Progress lines until "done" (the result is written) or the end of
    // its stdout (it died). Cancel is polled all the while: the worker is
    // killed, not asked.
    double lastFraction = 0.0;
    std::string lastStage = "Reading with Assimp";
    reportProgress(progress, 0.0, lastStage);
    char chunk[4096];
    // The watchdog: progress that stops changing for this long means a
    // reader that spins (Assimp 5.2.5 on some damaged files) or waits.
    auto lastChange = Clock::now();
    for (;;) {
      if (isCancelled(progress)) return cancelled();
      if (limits_.watchdogSeconds > 0 &&
          std::chrono::duration<double>(Clock::now() - lastChange).count() > limits_.watchdogSeconds) {
        stop(true);
        char secs[32];
        std::snprintf(secs, sizeof secs, "%g", limits_.watchdogSeconds);
        return failed(path + ": the " + formatName(path) + " reader (Assimp) made no progress for " + secs +
                      " s (stuck at " + std::to_string(int(lastFraction * 100.0)) + "%, '" + lastStage +
                      "'), so the import watchdog stopped it; the file is probably damaged (HS_IMPORT_WATCHDOG_S "
                      "sets the time). Nothing was imported.");
      }
      pollfd p{fds_.progressRead, POLLIN, 0};
      const int n = ::poll(&p, 1, 50);
      if (n < 0 && errno != EINTR) break;
      if (n <= 0) continue;
      const ssize_t got = ::read(fds_.progressRead, chunk, sizeof chunk);
      if (got < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (got <= 0) break;  // end: the worker is gone
      buffer_.append(chunk, size_t(got));
      size_t nl;
      while ((nl = buffer_.find('\n')) != std::string::npos) {
        const std::string_view line = std::string_view(buffer_).substr(0, nl);
        if (line == mesh::kImportDoneLine) {
          buffer_.erase(0, nl + 1);
          return result(since, /*ended=*/false, 0);
        }
        double f;
        std::string stage;
        if (mesh::parseImportProgressLine(line, f, stage)) {
          if (std::clamp(f, 0.0, 1.0) != lastFraction || stage != lastStage) lastChange = Clock::now();
          lastFraction = std::clamp(f, 0.0, 1.0);
          lastStage = std::move(stage);
          reportProgress(progress, lastFraction, lastStage);
        }
        buffer_.erase(0, nl + 1);
      }
    }
    return ended(progress, since);
  }

  // Closes its stdin (it ends at once) and reaps it; `kill` first with SIGKILL.
  void stop(bool kill = false) {
    if (pid_ <= 0) return;
    Fds::closeOne(fds_.stdinWrite);
    if (kill) {
      killAndReap(pid_);
    } else {
      // It exits when it sees the end of stdin; a worker that does not
      // within a second is killed.
      const auto deadline = Clock::now() + std::chrono::seconds(1);
      int status = 0;
      pid_t w = 0;
      while ((w = ::waitpid(pid_, &status, WNOHANG)) == 0 && Clock::now() < deadline) ::poll(nullptr, 0, 5);
      if (w == 0) killAndReap(pid_);
    }
    pid_ = -1;
  }

 private:
  mesh::ImportResult failed(std::string error) const {
    mesh::ImportResult out;
    out.report.file = *path_;
    out.report.reader = "assimp";
    out.error = std::move(error);
    return out;
  }

  mesh::ImportResult cancelled() {
    stop(true);
    mesh::ImportResult out = failed(*path_ + ": import cancelled");
    out.cancelled = true;
    return out;
  }

  // The result the worker wrote; `ended`: it is gone, with this exit code.
  mesh::ImportResult result(Clock::time_point since, bool ended, int code) {
    std::string readError;
    mesh::ImportResult r;
    bool haveResult = false;
    const int dupFd = ::dup(fds_.result);
    if (std::FILE* in = dupFd >= 0 ? ::fdopen(dupFd, "rb") : nullptr) {
      haveResult = mesh::readImportResult(in, r, readError);
      std::fclose(in);
    } else {
      if (dupFd >= 0) ::close(dupFd);
      readError = std::strerror(errno);
    }
    if (!haveResult) {
      if (!ended) stop(true);  // it said "done" over a torn result: not to be trusted with another file
      const std::string said = ended ? lastLine(fds_.err) : std::string();
      return withoutResult(ended ? exitText(code) : std::string("it said it was done"),
                           !said.empty() ? said : readError);
    }
    // Read: cut it, so that if this worker ends without writing the next
    // file's result it can never hand back this file's mesh instead. (Not
    // before a request: a worker just started may already be writing.) A
    // worker whose file cannot be cut is not used again.
    if (!ended && ::ftruncate(fds_.result, 0) != 0) stop(true);
    r.report.seconds = std::chrono::duration<double>(Clock::now() - since).count();
    // The worker names the file and the stage; the limit is ours to name.
    if (!r.ok() && limits_.memoryBytes && r.error.find("ran out of memory") != std::string::npos)
      r.error += " (the import worker's memory limit: " + mib(limits_.memoryBytes) + ", " + limits_.memoryText +
                 "; HS_IMPORT_MEMORY_LIMIT sets it)";
    return r;
  }

  // The worker's stdout ended: it is ending or gone. Cancel still holds
  // while it does; then its exit says what happened.
  mesh::ImportResult ended(const Progress* progress, Clock::time_point since = Clock::now()) {
    int status = 0;
    bool reaped = false;
    for (;;) {
      const pid_t w = ::waitpid(pid_, &status, WNOHANG);
      if (w == pid_) {
        reaped = true;
        break;
      }
      if (w < 0 && errno != EINTR) break;  // ECHILD: someone else reaped it (SIGCHLD ignored); the result tells
      if (isCancelled(progress)) return cancelled();
      if (w == 0) ::poll(nullptr, 0, 5);
    }
    pid_ = -1;
    Fds::closeOne(fds_.stdinWrite);
    const std::string& path = *path_;
    const std::string reader = "the " + formatName(path) + " reader (Assimp)";
    // A reader that cannot allocate under the limit may abort instead of
    // failing cleanly; the worker said so on stderr (tools/import_worker).
    const std::string memory =
        limits_.memoryBytes ? " (The import worker's memory limit was " + mib(limits_.memoryBytes) + ", " +
                                  limits_.memoryText + "; HS_IMPORT_MEMORY_LIMIT sets it.)"
                            : std::string();
    if (reaped && WIFSIGNALED(status) && limits_.memoryBytes &&
        stderrTail(fds_.err).find("out of memory: an allocation failed under the memory limit") != std::string::npos)
      return failed(path + ": " + reader + " ran out of memory: it reached the import worker's memory limit of " +
                    mib(limits_.memoryBytes) + " (" + limits_.memoryText +
                    "; HS_IMPORT_MEMORY_LIMIT sets it) and stopped (" + signalName(WTERMSIG(status)) +
                    "). Nothing was imported.");
    if (reaped && WIFSIGNALED(status)) {
      const int sig = WTERMSIG(status);
      if (sig == SIGKILL)
        return failed(path + ": " + reader +
                      " was killed (SIGKILL) while reading this file, perhaps for using too much memory. Nothing was "
                      "imported." +
                      memory);
      return failed(path + ": " + reader + " crashed on this file (" + signalName(sig) +
                    "); it is probably damaged. Nothing was imported." + memory);
    }
    const int code = reaped && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == 0 || !reaped) return result(since, /*ended=*/true, code);
    return withoutResult(exitText(code), lastLine(fds_.err));
  }

  static std::string exitText(int code) {
    return code >= 0 ? "exit code " + std::to_string(code) : std::string("its exit status is unknown");
  }

  // "<file>: the <format> reader (Assimp) stopped without a result (<how>[: <detail>]). ..."
  mesh::ImportResult withoutResult(const std::string& how, const std::string& detail) const {
    return failed(*path_ + ": the " + formatName(*path_) + " reader (Assimp) stopped without a result (" + how +
                  (detail.empty() ? "" : ": " + detail) + "). Nothing was imported.");
  }

  pid_t pid_ = -1;
  Fds fds_;
  WorkerLimits limits_;
  std::string buffer_;  // progress bytes not yet a whole line
  const std::string* path_ = nullptr;  // the file being read (for messages)
};

}  // namespace

struct ImportWorkerPool::Impl {
  std::mutex mutex;
  std::vector<std::unique_ptr<WorkerProcess>> idle;
  unsigned started = 0;
};

ImportWorkerPool::ImportWorkerPool() : impl_(std::make_unique<Impl>()) {}
ImportWorkerPool::~ImportWorkerPool() = default;

unsigned ImportWorkerPool::workersStarted() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->started;
}

mesh::ImportResult ImportWorkerPool::read(const std::string& path, const mesh::ImportOptions& options,
                                          const Progress* progress) {
  if (!readsWithAssimp(path, options)) return mesh::importMesh(path, options, progress);
  const auto since = Clock::now();
  std::string lookedAt, why;
  WorkerLimits limits;
  if (!workerLimits(limits, why)) {
    mesh::ImportResult r;
    r.report.file = path;
    r.report.reader = "assimp";
    r.error = path + ": not read: " + why;
    return r;
  }
  std::unique_ptr<WorkerProcess> worker;
  {
    std::lock_guard lock(impl_->mutex);
    if (!impl_->idle.empty()) {
      worker = std::move(impl_->idle.back());
      impl_->idle.pop_back();
    }
  }
  if (!worker) {
    const std::string program = findImportWorker(&lookedAt);
    if (program.empty()) {
      why = std::string(kWorkerName) + " not found" + (lookedAt.empty() ? "" : " (looked at " + lookedAt + ")");
    } else {
      worker = std::make_unique<WorkerProcess>();
      if (worker->start(program, limits, why)) {
        std::lock_guard lock(impl_->mutex);
        ++impl_->started;
      } else {
        worker.reset();
      }
    }
  }
  if (!worker) {
    mesh::ImportResult r = mesh::importMesh(path, options, progress);
    r.report.warnings.push_back(path + ": read inside this process, not in the import worker (" + why +
                                "); a reader crash on a damaged file would end the program");
    return r;
  }
  mesh::ImportResult r = worker->read(path, options, progress, since);
  if (worker->running()) {
    std::lock_guard lock(impl_->mutex);
    impl_->idle.push_back(std::move(worker));
  }
  return r;
}

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
  // A share of what this process may use: the machine's memory, or its
  // control group's limit where lower (a Slurm job, a container).
  const MemoryLimit available = memoryLimit();
  limits.usableBytes = available.bytes;
  const double usable = double(available.bytes);
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
    limits.memoryBytes = uint64_t(std::max(percent ? usable * value / 100.0 : value * 1048576.0, 67108864.0));
    char what[96];
    if (percent) std::snprintf(what, sizeof what, "%s of %.1f GiB", text.c_str(), usable / 1073741824.0);
    else std::snprintf(what, sizeof what, "set to %s MiB", text.c_str());
    limits.memoryText = what;
    if (percent && !available.cgroup.empty())
      limits.memoryText += ", the memory limit of control group " + available.cgroup;
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
  unsigned n = availableThreads();
  WorkerLimits limits;
  std::string ignored;  // a bad setting is reported by the tile's own read
  if (workerLimits(limits, ignored) && limits.memoryBytes > 0) {
    n = std::min(n, unsigned(std::max(1.0, std::floor(double(limits.usableBytes) / double(limits.memoryBytes)))));
  }
  return std::max(1u, std::min<unsigned>(n, unsigned(paths.size())));
}

mesh::ImportResult importMeshIsolated(const std::string& path, const mesh::ImportOptions& options,
                                      const Progress* progress) {
  ImportWorkerPool pool;
  return pool.read(path, options, progress);
}

}  // namespace hs::scene

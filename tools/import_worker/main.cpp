// hybridscape-import-worker: reads mesh files with mesh::importMesh in a
// process of its own, so a reader that crashes on a damaged file (Assimp
// 5.2.5 does: double free, abort, segfault) takes only this process down.
// Started by scene/import_isolation.cpp; the protocol is mesh/import_wire.h.
//
//   hybridscape-import-worker (--result-fd N | --out FILE) [--watch-stdin]
//                             [--memory-limit-mb N] [import options] -- <mesh-file>
//   hybridscape-import-worker --result-fd N --serve [--memory-limit-mb N]
//
// Progress goes to stdout as "progress <fraction> <stage>" lines; the result
// (mesh, report, or the reader's error) to the descriptor or file. Exit code
// 0 when a result was written (also for a file that could not be read: the
// error is in the result), 2 for bad arguments, 3 if the result could not be
// written. --watch-stdin: stop when stdin reaches its end (the parent closed
// its side, or died), so no worker outlives the program that wanted it.
// --serve: one file per request read from stdin (a multi-tile import keeps
// one worker for all its tiles instead of paying ~0.2 s to start one per
// tile); each result is rewritten from the start of the descriptor and
// followed by a "done" line on stdout; the end of stdin ends the worker at
// once, between files or in the middle of one.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <exception>
#include <new>
#include <system_error>
#include <string>
#include <thread>
#include <vector>

#include "core/image_io.h"
#include "mesh/import_wire.h"
#include "mesh/mesh_import.h"

namespace {

int usage(const std::string& why) {
  std::fprintf(stderr,
               "hybridscape-import-worker: %s\n"
               "usage: hybridscape-import-worker (--result-fd N | --out FILE) [--watch-stdin] [options] -- <mesh-file>\n"
               "(started by Hybridscape to read a mesh in a process of its own)\n",
               why.c_str());
  return 2;
}

void writeAll(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the parent stopped listening; the import goes on
    done += size_t(n);
  }
}

// Under --memory-limit-mb an allocation can fail anywhere, also where a
// reader cannot pass the std::bad_alloc on (a noexcept destructor, a
// thread) and the process aborts. This line on stderr lets the parent say
// it was the limit, not a damaged file (scene/import_isolation.cpp).
void sayOutOfMemory() {
  static const char kLine[] = "\nhybridscape-import-worker: out of memory: an allocation failed under the memory limit\n";
  (void)!::write(STDERR_FILENO, kLine, sizeof kLine - 1);
}

void outOfMemory() {
  sayOutOfMemory();
  std::set_new_handler(nullptr);  // the next failure throws without coming back here
  throw std::bad_alloc();
}

// A thread that cannot get its stack under the limit ends in
// std::terminate with a std::system_error (EAGAIN): said the same way.
[[noreturn]] void terminateUnderLimit() {
  if (std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::bad_alloc&) {
      sayOutOfMemory();
    } catch (const std::system_error& se) {
      if (se.code() == std::errc::resource_unavailable_try_again || se.code() == std::errc::not_enough_memory)
        sayOutOfMemory();
    } catch (...) {
    }
  }
  std::abort();
}

// The import options and the file of one read: "--key value" pairs, then
// "--" and the file. False with `error` when they make no sense.
bool parseRead(const std::vector<std::string>& args, size_t from, hs::mesh::ImportOptions& options, std::string& path,
               std::string& error) {
  for (size_t i = from; i < args.size(); ++i) {
    if (args[i] == "--") {
      if (i + 2 != args.size()) {
        error = "expected exactly one file after --";
        return false;
      }
      path = args[i + 1];
      return true;
    }
    if (i + 1 >= args.size()) {
      error = args[i] + " needs a value";
      return false;
    }
    if (!hs::mesh::parseImportWorkerOptionArgument(args[i], args[i + 1], options, error)) return false;
    ++i;
  }
  error = "no mesh file given";
  return false;
}

// Writes `result` from the start of `fd` (a serving worker's earlier result
// is cut off first) or to `outPath`; false with errno's message in `error`.
bool writeResult(int fd, const std::string& outPath, const hs::mesh::ImportResult& result, std::string& error) {
  std::FILE* out = nullptr;
  if (fd >= 0) {
    if (::ftruncate(fd, 0) != 0 || ::lseek(fd, 0, SEEK_SET) != 0) {
      error = std::strerror(errno);
      return false;
    }
    const int copy = ::dup(fd);  // fclose closes the copy, the descriptor stays for the next request
    out = copy >= 0 ? fdopen(copy, "wb") : nullptr;
    if (!out && copy >= 0) ::close(copy);
  } else {
    out = std::fopen(outPath.c_str(), "wb");
  }
  if (!out) {
    error = std::strerror(errno);
    return false;
  }
  const bool written = hs::mesh::writeImportResult(out, result);
  const int savedErrno = errno;
  if (std::fclose(out) != 0 || !written) {
    error = std::strerror(savedErrno);
    return false;
  }
  return true;
}

// The address space mapped now (/proc/self/statm's first field), 0 where
// it cannot be read.
rlim_t addressSpaceNow() {
  unsigned long pages = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%lu", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  return rlim_t(pages) * rlim_t(sysconf(_SC_PAGESIZE));
}

// Around the image module's loading: the soft limit goes up to the hard
// one, and afterwards comes back raised by what the module mapped.
void liftLimitWhileLoading(bool before) {
  static rlim_t soft = 0, mappedBefore = 0;
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0) return;
  if (before) {
    soft = limit.rlim_cur, mappedBefore = addressSpaceNow();
    limit.rlim_cur = limit.rlim_max;
  } else {
    const rlim_t now = addressSpaceNow();
    const rlim_t added = now > mappedBefore ? now - mappedBefore : 0;
    limit.rlim_cur = soft == RLIM_INFINITY ? soft : std::min<rlim_t>(soft + added, limit.rlim_max);
  }
  setrlimit(RLIMIT_AS, &limit);
}

}  // namespace

int main(int argc, char** argv) {
  // A crash here is expected now and then (that is why this process exists):
  // no core file for it.
  const rlimit noCore{0, 0};
  setrlimit(RLIMIT_CORE, &noCore);
  // When memory runs out (RAM and swap, or a container's limit), the
  // kernel ends the process it scores worst, by size: that could be the
  // editor holding the user's unsaved scene rather than this worker
  // reading a huge file. 1000 makes this worker the first choice; its
  // parent then reports the worker killed (SIGKILL) and keeps its scene.
  // Any process may raise its own score; where /proc is missing, nothing
  // changes.
  if (FILE* adj = std::fopen("/proc/self/oom_score_adj", "w")) {
    std::fputs("1000", adj);
    std::fclose(adj);
  }

  int resultFd = -1;
  std::string outPath, path;
  bool watchStdin = false, serve = false;
  rlim_t memoryLimit = 0;  // 0: none
  hs::mesh::ImportOptions options;
  const std::vector<std::string> args(argv + 1, argv + argc);
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--watch-stdin" || a == "--serve") {
      (a == "--serve" ? serve : watchStdin) = true;
      continue;
    }
    if (a != "--result-fd" && a != "--out" && a != "--memory-limit-mb") {
      // The import options and the file (one-shot mode).
      std::string error;
      if (!parseRead(args, i, options, path, error)) return usage(error);
      break;
    }
    if (i + 1 >= args.size()) return usage(a + " needs a value");
    const std::string& v = args[++i];
    if (a == "--result-fd") {
      char* end = nullptr;
      resultFd = int(std::strtol(v.c_str(), &end, 10));
      if (!end || *end || resultFd < 0) return usage("--result-fd: bad value '" + v + "'");
    } else if (a == "--out") {
      outPath = v;
    } else {
      // Address space, not resident memory: what a reader asks for is
      // refused at once (a bad_alloc importMesh names), not after it has
      // pushed the machine into swap.
      char* end = nullptr;
      const unsigned long long mb = std::strtoull(v.c_str(), &end, 10);
      if (!end || *end || mb == 0 || mb > (1ull << 40)) return usage("--memory-limit-mb: bad value '" + v + "'");
      memoryLimit = rlim_t(mb) << 20;
    }
  }
  if (serve ? (resultFd < 0 || !path.empty()) : path.empty())
    return usage(serve ? "--serve needs --result-fd and takes its files as requests" : "no mesh file given");
  if (!serve && (resultFd < 0) == outPath.empty()) return usage("give one of --result-fd and --out");

  // Requests (--serve) come on stdin; its end, in either mode, ends this
  // process at once: the parent closed its side or died.
  std::mutex queueMutex;
  std::condition_variable queued;
  std::deque<std::vector<std::string>> requests;
  if (watchStdin && !serve)
    std::thread([] {
      char buf[256];
      for (;;) {
        const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
        if (n == 0 || (n < 0 && errno != EINTR)) _exit(4);
      }
    }).detach();
  if (serve)
    std::thread([&] {
      for (;;) {
        std::vector<std::string> request;
        std::string error;
        if (!hs::mesh::readImportRequest(stdin, request, error)) {
          if (!error.empty()) std::fprintf(stderr, "hybridscape-import-worker: %s\n", error.c_str());
          _exit(error.empty() ? 0 : 2);
        }
        std::lock_guard lock(queueMutex);
        requests.push_back(std::move(request));
        queued.notify_one();
      }
    }).detach();

  // Progress lines: only changes of 0.5% or a new stage, whole lines at once.
  std::mutex mutex;
  int lastPermille = -10;
  std::string lastStage;
  hs::Progress progress([&](double f, std::string_view stage) {
    std::lock_guard lock(mutex);
    const int permille = int(f * 1000.0);
    if (permille - lastPermille < 5 && stage == lastStage) return;
    lastPermille = permille;
    lastStage = stage;
    writeAll(STDOUT_FILENO, hs::mesh::importProgressLine(f, stage));
  });

  // The limit starts here, after our own threads have their stacks, and
  // bounds what reading adds to the address space the worker then has:
  // its libraries map hundreds of MiB, so an absolute limit of 512 MiB
  // (half of a 1 GiB job) once left nothing and even a 2 KB file "ran out
  // of memory". Only the soft limit is set, so that it can be lifted while
  // the image module loads (on the first texture, core/image_io.h: its
  // ~260 libraries map 500-700 MiB more, which are not the file's doing
  // either); loading it up front cost every worker 0.4 s, textures or not.
  if (memoryLimit) {
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) != 0) limit = {RLIM_INFINITY, RLIM_INFINITY};
    // A limit already set from outside (ulimit -v) and lower stays: we
    // only ever lower it.
    limit.rlim_cur = std::min<rlim_t>(addressSpaceNow() + memoryLimit, limit.rlim_max);
    if (setrlimit(RLIMIT_AS, &limit) != 0)
      return usage("--memory-limit-mb: cannot set the limit: " + std::string(std::strerror(errno)));
    hs::image_io::setLoadHook(liftLimitWhileLoading);
    std::set_new_handler(outOfMemory);
    std::set_terminate(terminateUnderLimit);
  }

  if (!serve) {
    const hs::mesh::ImportResult result = hs::mesh::importMesh(path, options, &progress);
    std::string error;
    if (!writeResult(resultFd, outPath, result, error)) {
      std::fprintf(stderr, "hybridscape-import-worker: cannot write the result: %s\n", error.c_str());
      return 3;
    }
    return 0;
  }
  for (;;) {
    std::vector<std::string> request;
    {
      std::unique_lock lock(queueMutex);
      queued.wait(lock, [&] { return !requests.empty(); });
      request = std::move(requests.front());
      requests.pop_front();
    }
    hs::mesh::ImportOptions readOptions;
    std::string readPath, error;
    if (!parseRead(request, 0, readOptions, readPath, error)) {
      std::fprintf(stderr, "hybridscape-import-worker: a request: %s\n", error.c_str());
      return 2;
    }
    {
      std::lock_guard lock(mutex);
      lastPermille = -10;
      lastStage.clear();
    }
    const hs::mesh::ImportResult result = hs::mesh::importMesh(readPath, readOptions, &progress);
    if (!writeResult(resultFd, {}, result, error)) {
      std::fprintf(stderr, "hybridscape-import-worker: cannot write the result: %s\n", error.c_str());
      return 3;
    }
    std::lock_guard lock(mutex);  // after the last progress line
    writeAll(STDOUT_FILENO, std::string(hs::mesh::kImportDoneLine) + "\n");
  }
}

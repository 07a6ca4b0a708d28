// hybridscape-import-worker: reads one mesh file with mesh::importMesh in a
// process of its own, so a reader that crashes on a damaged file (Assimp
// 5.2.5 does: double free, abort, segfault) takes only this process down.
// Started by scene/import_isolation.cpp; the protocol is scene/import_wire.h.
//
//   hybridscape-import-worker (--result-fd N | --out FILE) [--watch-stdin]
//                             [--memory-limit-mb N] [import options] -- <mesh-file>
//
// Progress goes to stdout as "progress <fraction> <stage>" lines; the result
// (mesh, report, or the reader's error) to the descriptor or file. Exit code
// 0 when a result was written (also for a file that could not be read: the
// error is in the result), 2 for bad arguments, 3 if the result could not be
// written. --watch-stdin: stop when stdin reaches its end (the parent closed
// its side, or died), so no worker outlives the program that wanted it.
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <exception>
#include <new>
#include <system_error>
#include <string>
#include <thread>

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

}  // namespace

int main(int argc, char** argv) {
  // A crash here is expected now and then (that is why this process exists):
  // no core file for it.
  const rlimit noCore{0, 0};
  setrlimit(RLIMIT_CORE, &noCore);

  int resultFd = -1;
  std::string outPath, path;
  bool watchStdin = false;
  rlim_t memoryLimit = 0;  // 0: none
  hs::mesh::ImportOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") {
      if (i + 2 != argc) return usage("expected exactly one file after --");
      path = argv[i + 1];
      break;
    }
    if (a == "--watch-stdin") {
      watchStdin = true;
      continue;
    }
    if (i + 1 >= argc) return usage(a + " needs a value");
    const std::string v = argv[++i];
    std::string error;
    if (a == "--result-fd") {
      char* end = nullptr;
      resultFd = int(std::strtol(v.c_str(), &end, 10));
      if (!end || *end || resultFd < 0) return usage("--result-fd: bad value '" + v + "'");
    } else if (a == "--out") {
      outPath = v;
    } else if (a == "--memory-limit-mb") {
      // Address space, not resident memory: what a reader asks for is
      // refused at once (a bad_alloc importMesh names), not after it has
      // pushed the machine into swap.
      char* end = nullptr;
      const unsigned long long mb = std::strtoull(v.c_str(), &end, 10);
      if (!end || *end || mb == 0 || mb > (1ull << 40)) return usage("--memory-limit-mb: bad value '" + v + "'");
      memoryLimit = rlim_t(mb) << 20;
    } else if (!hs::mesh::parseImportWorkerOptionArgument(a, v, options, error)) {
      return usage(error);
    }
  }
  if (path.empty()) return usage("no mesh file given");
  if ((resultFd < 0) == outPath.empty()) return usage("give one of --result-fd and --out");

  if (watchStdin)
    std::thread([] {
      char buf[256];
      for (;;) {
        const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
        if (n == 0 || (n < 0 && errno != EINTR)) _exit(4);
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

  // The limit starts here, after our own thread has its stack.
  if (memoryLimit) {
    // A limit already set from outside (ulimit -v) and lower stays: we
    // only ever lower it.
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_max != RLIM_INFINITY && limit.rlim_max < memoryLimit)
      memoryLimit = limit.rlim_max;
    limit = {memoryLimit, memoryLimit};
    if (setrlimit(RLIMIT_AS, &limit) != 0)
      return usage("--memory-limit-mb: cannot set the limit: " + std::string(std::strerror(errno)));
    std::set_new_handler(outOfMemory);
    std::set_terminate(terminateUnderLimit);
  }
  const hs::mesh::ImportResult result = hs::mesh::importMesh(path, options, &progress);

  std::FILE* out = resultFd >= 0 ? fdopen(resultFd, "wb") : std::fopen(outPath.c_str(), "wb");
  if (!out) {
    std::fprintf(stderr, "hybridscape-import-worker: cannot write the result: %s\n", std::strerror(errno));
    return 3;
  }
  const bool written = hs::mesh::writeImportResult(out, result);
  const int savedErrno = errno;
  if (std::fclose(out) != 0 || !written) {
    std::fprintf(stderr, "hybridscape-import-worker: cannot write the result: %s\n", std::strerror(savedErrno));
    return 3;
  }
  return 0;
}

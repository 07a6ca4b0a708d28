// core/parallel's thread count: allowedCpus() is the calling thread's
// affinity mask (checked against the kernel's own list in
// /proc/thread-self/status, a reference read another way), a thread bound
// to one CPU sees one, and resolveThreads caps requests at what the
// process may use. The CLI's side (no oneTBB warning, one decimation
// thread when bound to one CPU) is in tests/cli/test_cli_mesh.cpp.
#include <QtTest>

#include <sched.h>

#include <fstream>
#include <string>

#include "core/parallel.h"

using namespace hs;

namespace {

// The CPUs in the kernel's "Cpus_allowed_list" of the calling thread
// ("0-3,8,10-11"), or -1 when it cannot be read.
int kernelAllowedCpus() {
  std::ifstream in("/proc/thread-self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("Cpus_allowed_list:", 0) != 0) continue;
    int count = 0;
    size_t i = line.find(':') + 1;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',')) ++i;
      if (i >= line.size()) break;
      size_t used = 0;
      const int first = std::stoi(line.substr(i), &used);
      i += used;
      int last = first;
      if (i < line.size() && line[i] == '-') {
        last = std::stoi(line.substr(i + 1), &used);
        i += 1 + used;
      }
      count += last - first + 1;
    }
    return count;
  }
  return -1;
}

}  // namespace

class TestThreads : public QObject {
  Q_OBJECT

 private slots:
  void allowedCpusIsTheKernelsList() {
    const int kernel = kernelAllowedCpus();
    QVERIFY2(kernel > 0, "no Cpus_allowed_list in /proc/thread-self/status");
    QCOMPARE(int(allowedCpus()), kernel);
  }

  void aThreadBoundToOneCpuSeesOne() {
    cpu_set_t before;
    CPU_ZERO(&before);
    QCOMPARE(sched_getaffinity(0, sizeof before, &before), 0);
    int first = 0;
    while (first < CPU_SETSIZE && !CPU_ISSET(first, &before)) ++first;
    QVERIFY(first < CPU_SETSIZE);
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    QCOMPARE(sched_setaffinity(0, sizeof one, &one), 0);  // this thread only
    const unsigned bound = allowedCpus();
    const int kernelBound = kernelAllowedCpus();
    QCOMPARE(sched_setaffinity(0, sizeof before, &before), 0);
    QCOMPARE(bound, 1u);
    QCOMPARE(kernelBound, 1);
    QCOMPARE(int(allowedCpus()), CPU_COUNT(&before));
  }

  void requestsAreCappedAtTheAvailableThreads() {
    const unsigned n = availableThreads();
    QVERIFY(n >= 1);
    QCOMPARE(availableThreads(), n);  // kept from the first call
    QCOMPARE(resolveThreads(0u), n);
    QCOMPARE(resolveThreads(-3), int(n));
    QCOMPARE(resolveThreads(1u), 1u);
    QCOMPARE(resolveThreads(n + 100), n);
  }
};

QTEST_GUILESS_MAIN(TestThreads)
#include "test_threads.moc"

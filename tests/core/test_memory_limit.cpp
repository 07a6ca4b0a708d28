// core/memory_limit: the memory a process may use is the lower of the
// machine's and its control group's limit. The parser is checked on
// made-up /proc and cgroup trees (v1 and v2, nested limits, a container's
// mount whose top is its own group, escaped mount points, malformed
// files), and memoryLimit() against the kernel: a child moved into a
// memory group made here, with a limit set through the kernel's files,
// must see that limit.
#include <QtTest>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/memory_limit.h"
#include "memory_group.h"

using namespace hs;
namespace fs = std::filesystem;

namespace {

void writeFile(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

constexpr uint64_t GiB = uint64_t(1) << 30;

}  // namespace

class TestMemoryLimit : public QObject {
  Q_OBJECT
  QTemporaryDir dir_;
  std::string root() const { return dir_.path().toStdString(); }

 private slots:
  void v2TakesTheLowestLimitOnTheWayUp() {
    const std::string r = root() + "/v2";
    const std::string mi = "30 22 0:27 / /sys/fs/cgroup rw,nosuid - cgroup2 cgroup2 rw,nsdelegate\n";
    writeFile(r + "/sys/fs/cgroup/slurm/memory.max", "max\n");
    writeFile(r + "/sys/fs/cgroup/slurm/job_42/memory.max", "3221225472\n");
    writeFile(r + "/sys/fs/cgroup/slurm/job_42/step_0/memory.max", "max\n");
    std::string where;
    QCOMPARE(cgroupMemoryLimit("0::/slurm/job_42/step_0\n", mi, r, &where), 3 * GiB);
    QCOMPARE(where, std::string("/slurm/job_42"));
    // A parent's lower limit binds the child.
    writeFile(r + "/sys/fs/cgroup/slurm/memory.max", "1073741824\n");
    QCOMPARE(cgroupMemoryLimit("0::/slurm/job_42/step_0\n", mi, r, &where), GiB);
    QCOMPARE(where, std::string("/slurm"));
    // No "0::" line: this process is in no v2 group there.
    QCOMPARE(cgroupMemoryLimit("4:memory:/slurm/job_42\n", mi, r), uint64_t(0));
  }

  void v1ReadsTheMemoryControllersHierarchyOnly() {
    const std::string r = root() + "/v1";
    const std::string mi =
        "31 30 0:28 / /sys/fs/cgroup/cpu rw,relatime - cgroup cgroup rw,cpu\n"
        "34 30 0:31 / /sys/fs/cgroup/memory rw,relatime - cgroup cgroup rw,memory\n";
    const std::string cg = "8:cpu,cpuacct:/job\n4:memory:/process_api/abc\n0::/\n";
    // v1's "no limit": LONG_MAX rounded down to a page.
    writeFile(r + "/sys/fs/cgroup/memory/memory.limit_in_bytes", "9223372036854771712\n");
    writeFile(r + "/sys/fs/cgroup/memory/process_api/abc/memory.limit_in_bytes", "9223372036854771712\n");
    writeFile(r + "/sys/fs/cgroup/cpu/job/memory.limit_in_bytes", "1024\n");  // not a memory hierarchy
    QCOMPARE(cgroupMemoryLimit(cg, mi, r), uint64_t(0));
    writeFile(r + "/sys/fs/cgroup/memory/process_api/memory.limit_in_bytes", "2147483648\n");
    std::string where;
    QCOMPARE(cgroupMemoryLimit(cg, mi, r, &where), 2 * GiB);
    QCOMPARE(where, std::string("/process_api"));
  }

  void aContainersMountStartsAtItsOwnGroup() {
    // Docker without a cgroup namespace: /proc/self/cgroup names the full
    // group, and the mount's top is that group.
    const std::string r = root() + "/docker";
    const std::string mi = "40 35 0:30 /docker/f00d /sys/fs/cgroup ro,nosuid - cgroup2 cgroup2 rw\n";
    writeFile(r + "/sys/fs/cgroup/memory.max", "536870912\n");
    writeFile(r + "/sys/fs/cgroup/inner/memory.max", "max\n");
    QCOMPARE(cgroupMemoryLimit("0::/docker/f00d\n", mi, r), GiB / 2);
    QCOMPARE(cgroupMemoryLimit("0::/docker/f00d/inner\n", mi, r), GiB / 2);
    // A group outside the mount's view is read at the mount's top.
    QCOMPARE(cgroupMemoryLimit("0::/elsewhere\n", mi, r), GiB / 2);
  }

  void escapedMountPointsAreDecoded() {
    const std::string r = root() + "/escaped";
    const std::string mi = "30 22 0:27 / /mnt/cg\\040two rw - cgroup2 cgroup2 rw\n";
    writeFile(r + "/mnt/cg two/a/memory.max", "4096\n");
    QCOMPARE(cgroupMemoryLimit("0::/a\n", mi, r), uint64_t(4096));
  }

  void malformedFilesAreNoLimit() {
    const std::string r = root() + "/bad";
    const std::string mi = "30 22 0:27 / /cg rw - cgroup2 cgroup2 rw\n";
    for (const char* text : {"", "lots\n", "-5\n", "12abc\n", "0\n", "99999999999999999999999\n"}) {
      writeFile(r + "/cg/g/memory.max", text);
      QCOMPARE(cgroupMemoryLimit("0::/g\n", mi, r), uint64_t(0));
    }
    // Lines that are not mountinfo or cgroup lines at all.
    QCOMPARE(cgroupMemoryLimit("garbage\n::\n", "no dash here\n - \n", r), uint64_t(0));
    QCOMPARE(cgroupMemoryLimit("", "", r), uint64_t(0));
    // A path that tries to leave the hierarchy is read at its top.
    writeFile(r + "/cg/memory.max", "8192\n");
    writeFile(r + "/outside/memory.max", "4096\n");
    QCOMPARE(cgroupMemoryLimit("0::/../outside\n", mi, r), uint64_t(8192));
  }

  void thisProcessIsBoundedByThePhysicalMemory() {
    const MemoryLimit m = memoryLimit();
    const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    QCOMPARE(double(m.physicalBytes), physical);
    QVERIFY(m.bytes > 0 && m.bytes <= m.physicalBytes);
    QCOMPARE(m.cgroup.empty(), m.bytes == m.physicalBytes);
  }

  // The kernel's own files: a memory group made here (memory_group.h) with
  // a limit below the machine's memory, and a child moved into it.
  void aChildInALimitedGroupSeesTheLimit() {
    const uint64_t limit = 768ull << 20;  // below any machine this runs on
    const hs::test::MemoryGroup group(limit);
    if (!group.made)
      QSKIP(qPrintable(QString::fromStdString("no memory control group can be made here (" + group.why +
                                              "): the parser is checked on made-up trees above")));
    int fds[2];
    QVERIFY(pipe(fds) == 0);
    const pid_t child = fork();
    QVERIFY(child >= 0);
    if (child == 0) {
      ::close(fds[0]);
      if (!group.join()) _exit(2);
      const MemoryLimit m = memoryLimit();
      const std::string out = std::to_string(m.bytes) + " " + m.cgroup;
      _exit(::write(fds[1], out.data(), out.size()) == ssize_t(out.size()) ? 0 : 1);
    }
    ::close(fds[1]);
    std::string got;
    char buf[256];
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) got.append(buf, size_t(n));
    ::close(fds[0]);
    int status = 0;
    QCOMPARE(waitpid(child, &status, 0), child);
    QVERIFY2(WIFEXITED(status) && WEXITSTATUS(status) == 0, qPrintable(QString::number(status)));
    QCOMPARE(got, std::to_string(limit) + " " + group.relative);
  }
};

QTEST_GUILESS_MAIN(TestMemoryLimit)
#include "test_memory_limit.moc"

#pragma once
// A memory control group made for a test, with a limit set through the
// kernel's own files, into which a forked child moves itself: how a Slurm
// job or a container bounds a process. Found here independently of
// core/memory_limit (plain parsing of /proc/self/mountinfo and
// /proc/self/cgroup), so tests compare that code with the kernel, not with
// itself. cgroup v1: a group under this process's own in the memory
// hierarchy; v2: only when this process is at the hierarchy's root (the one
// group where the memory controller can be handed to a child while holding
// processes). Needs the right to make groups (root, as on this project's
// machines and CI); `made` is false otherwise, with `why`.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace hs::test {

class MemoryGroup {
 public:
  explicit MemoryGroup(uint64_t limitBytes) {
    std::string v1Mount, v2Mount, v1Group, v2Group, line;
    std::istringstream mounts(read("/proc/self/mountinfo")), groups(read("/proc/self/cgroup"));
    while (std::getline(mounts, line)) {
      const size_t dash = line.find(" - ");
      if (dash == std::string::npos) continue;
      std::istringstream b(line.substr(0, dash)), a(line.substr(dash + 3));
      std::string id, parent, dev, top, point, type, source, options;
      b >> id >> parent >> dev >> top >> point;
      a >> type >> source >> options;
      if (type == "cgroup" && top == "/" && ("," + options + ",").find(",memory,") != std::string::npos)
        v1Mount = point;
      if (type == "cgroup2" && top == "/") v2Mount = point;
    }
    while (std::getline(groups, line)) {
      if (line.rfind("0::", 0) == 0) v2Group = line.substr(3);
      const size_t c1 = line.find(':'), c2 = c1 == std::string::npos ? c1 : line.find(':', c1 + 1);
      if (c2 != std::string::npos && ("," + line.substr(c1 + 1, c2 - c1 - 1) + ",").find(",memory,") != std::string::npos)
        v1Group = line.substr(c2 + 1);
    }
    std::string base, own;
    if (!v1Mount.empty() && !v1Group.empty()) {
      own = v1Group == "/" ? "" : v1Group;
      base = v1Mount + own;
      file_ = "memory.limit_in_bytes";
    } else if (!v2Mount.empty() && v2Group == "/" && read(v2Mount + "/cgroup.controllers").find("memory") != std::string::npos) {
      std::ofstream(v2Mount + "/cgroup.subtree_control") << "+memory";
      base = v2Mount;
      file_ = "memory.max";
    } else {
      why = "no cgroup v1 memory hierarchy, and not at the root of a v2 one with the memory controller";
      return;
    }
    const std::string leaf = "/hs_test_memory_group_" + std::to_string(::getpid());
    dir = base + leaf;
    relative = own + leaf;
    std::error_code ec;
    if (!std::filesystem::create_directory(dir, ec)) {
      why = "cannot make " + dir + ": " + ec.message();
      dir.clear();
      return;
    }
    { std::ofstream(dir + "/" + file_) << limitBytes; }
    made = read(dir + "/" + file_) == std::to_string(limitBytes) + "\n";
    if (!made) why = "the kernel did not take the limit in " + dir + "/" + file_;
  }
  ~MemoryGroup() {
    if (!dir.empty()) ::rmdir(dir.c_str());  // empty again once the children have ended
  }
  MemoryGroup(const MemoryGroup&) = delete;
  MemoryGroup& operator=(const MemoryGroup&) = delete;

  // In the forked child: moves the calling process into the group.
  bool join() const {
    std::ofstream procs(dir + "/cgroup.procs");
    procs << ::getpid();
    procs.flush();
    return bool(procs);
  }

  bool made = false;
  std::string why;       // when not made
  std::string dir;       // the group's directory
  std::string relative;  // the group as /proc/self/cgroup names it

 private:
  static std::string read(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::string file_;
};

}  // namespace hs::test

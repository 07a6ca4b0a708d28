#include "core/memory_limit.h"

#include <unistd.h>

#include <charconv>
#include <fstream>
#include <sstream>
#include <vector>

namespace hs {
namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string_view> split(std::string_view text, char sep) {
  std::vector<std::string_view> out;
  size_t start = 0;
  for (;;) {
    const size_t at = text.find(sep, start);
    out.push_back(text.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) break;
    start = at + 1;
  }
  return out;
}

bool hasToken(std::string_view list, std::string_view token) {
  for (const std::string_view t : split(list, ','))
    if (t == token) return true;
  return false;
}

// mountinfo writes a space, tab, newline or backslash in a path as \ooo.
std::string unescapeOctal(std::string_view s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    const auto octal = [&](size_t k, char top) { return s[k] >= '0' && s[k] <= top; };
    if (s[i] == '\\' && i + 3 < s.size() && octal(i + 1, '3') && octal(i + 2, '7') && octal(i + 3, '7')) {
      out += char((s[i + 1] - '0') * 64 + (s[i + 2] - '0') * 8 + (s[i + 3] - '0'));
      i += 3;
    } else {
      out += s[i];
    }
  }
  return out;
}

// A limit file's value: a byte count, or none ("max" in v2; v1's "no limit"
// is LONG_MAX rounded down to a page, 9223372036854771712, so anything from
// 2^62 on is taken as none).
uint64_t parseLimit(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v == 0) return 0;
  return v >= (uint64_t(1) << 62) ? 0 : v;
}

struct Hierarchy {
  std::string mountPoint, root;  // where it is mounted, and which of its groups is the mount's top
  bool v2 = false;
};

}  // namespace

uint64_t cgroupMemoryLimit(std::string_view procSelfCgroup, std::string_view mountinfo, const std::string& fsRoot,
                           std::string* where) {
  // The hierarchies that can hold a memory limit.
  std::vector<Hierarchy> mounts;
  for (const std::string_view line : split(mountinfo, '\n')) {
    // "36 35 0:30 / /sys/fs/cgroup/memory rw,nosuid - cgroup cgroup rw,memory"
    const size_t dash = line.find(" - ");
    if (dash == std::string_view::npos) continue;
    const std::vector<std::string_view> before = split(line.substr(0, dash), ' ');
    const std::vector<std::string_view> after = split(line.substr(dash + 3), ' ');
    if (before.size() < 5 || after.size() < 3) continue;
    const bool v2 = after[0] == "cgroup2";
    if (!v2 && !(after[0] == "cgroup" && hasToken(after[2], "memory"))) continue;
    mounts.push_back({unescapeOctal(before[4]), unescapeOctal(before[3]), v2});
  }
  // This process's group in each: "0::/path" (v2), "4:memory:/path" (v1).
  std::string pathV2, pathV1;
  bool haveV2 = false, haveV1 = false;
  for (const std::string_view line : split(procSelfCgroup, '\n')) {
    const size_t c1 = line.find(':');
    const size_t c2 = c1 == std::string_view::npos ? c1 : line.find(':', c1 + 1);
    if (c2 == std::string_view::npos) continue;
    const std::string_view controllers = line.substr(c1 + 1, c2 - c1 - 1), path = line.substr(c2 + 1);
    if (line.substr(0, c1) == "0" && controllers.empty()) pathV2 = path, haveV2 = true;
    else if (hasToken(controllers, "memory")) pathV1 = path, haveV1 = true;
  }

  uint64_t lowest = 0;
  for (const Hierarchy& h : mounts) {
    if (h.v2 ? !haveV2 : !haveV1) continue;
    std::string group = h.v2 ? pathV2 : pathV1;
    // The group relative to the mount: a container's mount often has its
    // own group as the top (root "/docker/<id>", group "/docker/<id>").
    // A group outside the mount (another namespace's view) is read at the
    // mount's top: the nearest limit this process can see.
    if (h.root != "/") {
      if (group == h.root) group = "/";
      else if (group.rfind(h.root + "/", 0) == 0) group = group.substr(h.root.size());
      else group = "/";
    }
    if (group.empty() || group[0] != '/' || group.find("/..") != std::string::npos) group = "/";
    const std::string file = h.v2 ? "memory.max" : "memory.limit_in_bytes";
    // From the group up to the mount's top: a parent's limit binds its
    // children too.
    for (std::string g = group;;) {
      const std::string dir = fsRoot + h.mountPoint + (g == "/" ? "" : g);
      const uint64_t v = parseLimit(readText(dir + "/" + file));
      if (v && (!lowest || v < lowest)) {
        lowest = v;
        if (where) *where = g;
      }
      if (g == "/") break;
      const size_t slash = g.rfind('/');
      g = slash == 0 ? "/" : g.substr(0, slash);
    }
  }
  return lowest;
}

MemoryLimit memoryLimit() {
  MemoryLimit m;
  const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
  m.physicalBytes = pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
  m.bytes = m.physicalBytes;
#ifdef __linux__
  std::string where;
  const uint64_t group =
      cgroupMemoryLimit(readText("/proc/self/cgroup"), readText("/proc/self/mountinfo"), std::string(), &where);
  if (group && (group < m.bytes || !m.bytes)) m.bytes = group, m.cgroup = where;
#endif
  return m;
}

}  // namespace hs

#pragma once
// The memory this process may use: the machine's physical memory, or less
// where a control group caps it. A Slurm job (cgroup memory enforcement), a
// container (docker --memory, Kubernetes limits) or a systemd slice runs
// under such a cap, and sizing work by the machine there oversteps the job:
// the kernel then kills inside the group instead of an allocation failing
// with a message. Linux only; elsewhere the physical memory.
#include <cstdint>
#include <string>
#include <string_view>

namespace hs {

struct MemoryLimit {
  uint64_t bytes = 0;          // what the process may use: min(physical, the group's limit)
  uint64_t physicalBytes = 0;  // the machine's memory
  std::string cgroup;          // the control group whose limit is lower than physical; empty: none is
};

// Read anew at every call (a job may be moved between groups).
MemoryLimit memoryLimit();

// The lowest memory limit on the way from the control group that
// `procSelfCgroup` (the text of /proc/self/cgroup) names up to its
// hierarchy's root, in every memory hierarchy that `mountinfo` (the text of
// /proc/self/mountinfo) lists: cgroup v2's memory.max, cgroup v1's
// memory.limit_in_bytes. Every mount point is read under `fsRoot` ("" for
// the real files; tests pass a directory holding a made-up tree). 0 when
// no group sets one; `where`, when given, gets the group's directory
// relative to its hierarchy ("/slurm/uid_1000/job_42"). Unreadable or
// malformed files count as no limit: this only ever lowers a budget.
uint64_t cgroupMemoryLimit(std::string_view procSelfCgroup, std::string_view mountinfo, const std::string& fsRoot,
                           std::string* where = nullptr);

}  // namespace hs

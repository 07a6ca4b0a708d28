#include "core/scratch_files.h"

#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <string_view>

#include <sys/types.h>
#include <unistd.h>

namespace hs {
namespace {

// The host as a name can hold it (host names are letters, digits, '-' and '.').
std::string hostPart() {
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0 || host[0] == 0) return "host";
  std::string h(host);
  for (char& c : h)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.')) c = '_';
  return h;
}

bool processRuns(long pid) {
  if (pid <= 0) return true;  // not a process id: keep it
  // Signal 0 checks without sending; EPERM: it runs, as another user.
  return ::kill(pid_t(pid), 0) == 0 || errno != ESRCH;
}

}  // namespace

std::string scratchName(const std::string& prefix, const std::string& suffix) {
  static std::atomic<unsigned> serial{0};
  return prefix + hostPart() + "-" + std::to_string(::getpid()) + "-" + std::to_string(serial++) + suffix;
}

size_t sweepStaleScratch(const std::filesystem::path& dir, const std::string& prefix) {
  namespace fs = std::filesystem;
  const std::string mine = prefix + hostPart() + "-";
  size_t removed = 0;
  std::error_code ec;
  fs::directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, mine.size(), mine) != 0) continue;
    const std::string_view rest = std::string_view(name).substr(mine.size());
    size_t digits = 0;
    while (digits < rest.size() && rest[digits] >= '0' && rest[digits] <= '9') ++digits;
    if (digits == 0 || digits > 9 || digits == rest.size() || rest[digits] != '-') continue;
    if (processRuns(std::stol(std::string(rest.substr(0, digits))))) continue;
    std::error_code rc;
    if (fs::remove_all(it->path(), rc) > 0 && !rc) ++removed;
  }
  return removed;
}

}  // namespace hs

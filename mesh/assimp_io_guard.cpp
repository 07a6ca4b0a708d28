#include "mesh/assimp_io_guard.h"

#include <sys/stat.h>

#include <algorithm>

#include <assimp/DefaultIOSystem.h>

namespace hs::mesh {
namespace {

// "" when `path` is a regular file (or does not exist: Assimp's own "not
// found" is the right message then); otherwise what it is.
std::string notRegular(const char* path) {
  struct stat st {};
  if (::stat(path, &st) != 0 || S_ISREG(st.st_mode)) return {};
  if (S_ISDIR(st.st_mode)) return "a directory";
  if (S_ISFIFO(st.st_mode)) return "a pipe (FIFO)";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  return "not a regular file";
}

class GuardedIo : public Assimp::DefaultIOSystem {
 public:
  // Some readers ask Exists() first (Assimp's OBJ reader for `mtllib`),
  // others only Open(); both refuse, and both say so once.
  bool Exists(const char* file) const override {
    return !refuse(file) && Assimp::DefaultIOSystem::Exists(file);
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    return refuse(file) ? nullptr : Assimp::DefaultIOSystem::Open(file, mode);
  }
  mutable std::vector<std::string> refused;

 private:
  bool refuse(const char* file) const {
    const std::string what = notRegular(file);
    if (what.empty()) return false;
    const std::string line = std::string(file) + " (" + what + "), not read";
    if (std::find(refused.begin(), refused.end(), line) == refused.end()) refused.push_back(line);
    return true;
  }
};

}  // namespace

struct AssimpIoGuard::Impl {
  GuardedIo io;
};

AssimpIoGuard::AssimpIoGuard() : impl_(std::make_unique<Impl>()) {}
AssimpIoGuard::~AssimpIoGuard() = default;
Assimp::IOSystem* AssimpIoGuard::io() { return &impl_->io; }
const std::vector<std::string>& AssimpIoGuard::refused() const { return impl_->io.refused; }

}  // namespace hs::mesh

#pragma once
// The files Assimp opens, through one door that refuses what is not a
// regular file. Assimp opens more than the mesh: an OBJ's `mtllib`, a
// glTF's buffers and images, an FBX's external textures. A path naming
// /dev/urandom, /dev/zero or a FIFO there reads forever or blocks; a
// directory fails in ways that differ by reader. Refused here, the reader
// sees "file not found" and says so in its own way (a warning for a
// material library, an error for a buffer), and `refused()` lists them for
// our report.
#include <memory>
#include <string>
#include <vector>

namespace Assimp {
class IOSystem;
}

namespace hs::mesh {

class AssimpIoGuard {
 public:
  AssimpIoGuard();
  ~AssimpIoGuard();
  // The IOSystem to hand to Assimp::Importer::SetIOHandler (the importer
  // does not own it: call SetIOHandler(nullptr) before this guard dies).
  Assimp::IOSystem* io();
  // "path (what it is), not read" for every file refused so far.
  const std::vector<std::string>& refused() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hs::mesh

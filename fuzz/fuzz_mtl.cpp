// The MTL reader on any bytes. It reads a path (readWholeFile), so the input
// goes to an in-memory file (memfd) named through /proc/self/fd.
#include <sys/mman.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "fuzz_target.h"
#include "mesh/mtl_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const int fd = memfd_create("fuzz.mtl", 0);
  if (fd < 0 || ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != ssize_t(size)) return 0;
  std::vector<hs::mesh::MtlMaterial> materials;
  std::vector<std::string> warnings;
  std::string error;
  hs::mesh::readMtl("/proc/self/fd/" + std::to_string(fd), materials, error, &warnings);
  return 0;
}

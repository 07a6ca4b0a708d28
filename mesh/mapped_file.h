#pragma once
// Read-only memory map of a whole file (POSIX), so multi-GB scans are parsed
// without first copying them into the heap.
#include <cstddef>
#include <string>
#include <string_view>

namespace hs::mesh {

class MappedFile {
 public:
  MappedFile() = default;
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  // False with `error` naming the file on failure (missing, a directory,
  // unreadable). A 0-byte file opens fine with an empty view.
  bool open(const std::string& path, std::string& error);
  std::string_view view() const { return {static_cast<const char*>(data_), size_}; }
  size_t size() const { return size_; }

 private:
  void* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace hs::mesh

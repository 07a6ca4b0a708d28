#pragma once
// Reading input files that may change while they are read (a scan still
// being copied, a file overwritten by another program). Every read goes
// through read()/pread() into our own memory: a file mapped with mmap
// kills the process with SIGBUS when it shrinks under the mapping, which a
// reader cannot catch, while a short read here is an error naming the file.
// Reading in pieces also bounds memory: a multi-GB scan is never held whole.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hs::mesh {

// An open file read in pieces at any offset, from any number of threads at
// once (the OBJ reader's chunks), or text already in memory behind the
// same calls. The size is the file's when it was opened.
class ByteSource {
 public:
  // A source with no bytes until open() succeeds.
  ByteSource() = default;
  // Text in memory, not copied (it must outlive the source); `name` is what
  // messages call it.
  ByteSource(std::string_view text, std::string name) : name_(std::move(name)), text_(text), size_(text.size()) {}
  ~ByteSource();
  ByteSource(const ByteSource&) = delete;
  ByteSource& operator=(const ByteSource&) = delete;

  // Opens `path` for reading. False with `error` naming it when it is
  // missing, a directory, not a regular file or unreadable. A 0-byte file
  // opens fine.
  bool open(const std::string& path, std::string& error);

  const std::string& name() const { return name_; }
  uint64_t size() const { return size_; }

  // The whole text when the source is text in memory; nullopt for a file.
  std::optional<std::string_view> inMemory() const {
    return fd_ < 0 ? std::optional<std::string_view>(text_) : std::nullopt;
  }

  // The bytes [offset, offset + n) (n clipped to the size): a view into the
  // text, or into `buffer` for a file. False with `error` naming the file
  // when it holds fewer bytes than when it was opened, or cannot be read.
  bool read(uint64_t offset, size_t n, std::string& buffer, std::string_view& out, std::string& error) const;
  // The same bytes copied to `out`, which has room for n; [offset, offset +
  // n) must lie within the size.
  bool readInto(uint64_t offset, size_t n, char* out, std::string& error) const;

  // False with `error` naming the file when its size or modification time
  // differs from when it was opened: it was written while we read it, so
  // what was read may mix two versions. Always true for text in memory.
  bool unchanged(std::string& error) const;

 private:
  std::string name_;
  std::string_view text_;  // the memory source
  int fd_ = -1;            // the file source
  uint64_t size_ = 0;
  int64_t mtimeSec_ = 0, mtimeNsec_ = 0;
};

// The whole of `path` into `out`, read with read() until its end. False with
// `error` naming the file when it cannot be opened or read, is a directory,
// or changed (size or modification time) while it was read.
bool readWholeFile(const std::string& path, std::string& out, std::string& error);
bool readWholeFile(const std::string& path, std::vector<uint8_t>& out, std::string& error);

}  // namespace hs::mesh

#include "mesh/byte_source.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace hs::mesh {
namespace {

std::string openError(const std::string& path, int err) {
  return path + ": " + (err == ENOENT ? std::string("file not found") : "cannot open: " + std::string(std::strerror(err)));
}

// Opens `path` read-only and checks it is a regular file; -1 with `error`.
int openRegular(const std::string& path, struct stat& st, std::string& error) {
  // stat before open: opening a FIFO for reading would block.
  if (::stat(path.c_str(), &st) != 0) {
    error = openError(path, errno);
    return -1;
  }
  if (S_ISDIR(st.st_mode)) {
    error = path + ": is a directory, not a file";
    return -1;
  }
  if (!S_ISREG(st.st_mode)) {
    error = path + ": is not a regular file";
    return -1;
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = openError(path, errno);
    return -1;
  }
  // The size and time that count are those of what we opened (the path
  // may have been replaced between stat and open).
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    error = path + ": is not a regular file";
    ::close(fd);
    return -1;
  }
  return fd;
}

std::string changedError(const std::string& path, uint64_t before, uint64_t now) {
  return path + ": the file changed while it was read (" + std::to_string(before) + " bytes when opened, " +
         std::to_string(now) + " now); read it again once whatever writes it has finished";
}

}  // namespace

ByteSource::~ByteSource() {
  if (fd_ >= 0) ::close(fd_);
}

bool ByteSource::open(const std::string& path, std::string& error) {
  struct stat st {};
  const int fd = openRegular(path, st, error);
  if (fd < 0) return false;
  if (fd_ >= 0) ::close(fd_);
  fd_ = fd;
  name_ = path;
  text_ = {};
  size_ = uint64_t(st.st_size);
  mtimeSec_ = st.st_mtim.tv_sec;
  mtimeNsec_ = st.st_mtim.tv_nsec;
  posix_fadvise(fd_, 0, 0, POSIX_FADV_SEQUENTIAL);
  return true;
}

bool ByteSource::read(uint64_t offset, size_t n, std::string& buffer, std::string_view& out,
                      std::string& error) const {
  if (offset >= size_) {
    out = {};
    return true;
  }
  n = size_t(std::min<uint64_t>(n, size_ - offset));
  if (fd_ < 0) {
    out = text_.substr(size_t(offset), n);
    return true;
  }
  // resize() would zero the bytes pread overwrites anyway; the buffer is
  // reused read after read, so this costs only on growth.
  if (buffer.size() < n) buffer.resize(n);
  if (!readInto(offset, n, buffer.data(), error)) return false;
  out = std::string_view(buffer.data(), n);
  return true;
}

bool ByteSource::readInto(uint64_t offset, size_t n, char* out, std::string& error) const {
  if (fd_ < 0) {
    std::memcpy(out, text_.data() + offset, n);
    return true;
  }
  size_t got = 0;
  while (got < n) {
    const ssize_t r = ::pread(fd_, out + got, n - got, off_t(offset + got));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      error = name_ + ": read failed at byte " + std::to_string(offset + got) + ": " + std::strerror(errno);
      return false;
    }
    if (r == 0) {
      error = name_ + ": the file shrank while it was read (" + std::to_string(size_) +
              " bytes when opened, it ends at byte " + std::to_string(offset + got) +
              " now); read it again once whatever writes it has finished";
      return false;
    }
    got += size_t(r);
  }
  return true;
}

bool ByteSource::unchanged(std::string& error) const {
  if (fd_ < 0) return true;
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    error = name_ + ": cannot check the file after reading: " + std::strerror(errno);
    return false;
  }
  if (uint64_t(st.st_size) != size_ || st.st_mtim.tv_sec != mtimeSec_ || st.st_mtim.tv_nsec != mtimeNsec_) {
    error = changedError(name_, size_, uint64_t(st.st_size));
    return false;
  }
  return true;
}

namespace {

template <class Bytes>
bool readWhole(const std::string& path, Bytes& out, std::string& error) {
  struct stat st {};
  const int fd = openRegular(path, st, error);
  if (fd < 0) return false;
  out.clear();
  // One more byte than the size asks for, so a file that grew is noticed
  // without a second call.
  out.resize(size_t(st.st_size) + 1);
  size_t got = 0;
  for (;;) {
    if (got == out.size()) out.resize(out.size() * 2);
    const ssize_t r = ::read(fd, reinterpret_cast<char*>(out.data()) + got, out.size() - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      error = path + ": read failed at byte " + std::to_string(got) + ": " + std::strerror(errno);
      ::close(fd);
      return false;
    }
    if (r == 0) break;
    got += size_t(r);
  }
  out.resize(got);
  struct stat after {};
  const bool statOk = ::fstat(fd, &after) == 0;
  const bool same = statOk && after.st_size == st.st_size && got == size_t(st.st_size) &&
                    after.st_mtim.tv_sec == st.st_mtim.tv_sec && after.st_mtim.tv_nsec == st.st_mtim.tv_nsec;
  ::close(fd);
  if (!same) {
    error = changedError(path, uint64_t(st.st_size), statOk ? uint64_t(after.st_size) : got);
    return false;
  }
  return true;
}

}  // namespace

bool readWholeFile(const std::string& path, std::string& out, std::string& error) {
  return readWhole(path, out, error);
}

bool readWholeFile(const std::string& path, std::vector<uint8_t>& out, std::string& error) {
  return readWhole(path, out, error);
}

}  // namespace hs::mesh

#include "mesh/mapped_file.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace hs::mesh {

MappedFile::~MappedFile() {
  if (data_ && size_) munmap(data_, size_);
}

bool MappedFile::open(const std::string& path, std::string& error) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    error = path + ": " + (errno == ENOENT ? std::string("file not found") : std::strerror(errno));
    return false;
  }
  if (S_ISDIR(st.st_mode)) {
    error = path + ": is a directory, not a mesh file";
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    error = path + ": is not a regular file";
    return false;
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  size_ = size_t(st.st_size);
  if (size_ > 0) {
    data_ = mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (data_ == MAP_FAILED) {
      data_ = nullptr;
      error = path + ": cannot map into memory: " + std::strerror(errno);
      ::close(fd);
      size_ = 0;
      return false;
    }
    madvise(data_, size_, MADV_SEQUENTIAL);
  }
  ::close(fd);
  return true;
}

}  // namespace hs::mesh

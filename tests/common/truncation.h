#pragma once
// Damaging files for the truncation tests of every reader: where to cut a
// file, and a thread that makes a file shrink and grow back under a reader
// (what a scan still being copied, or a file rewritten by another program,
// looks like to it).
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <string>
#include <thread>
#include <vector>

namespace hs::test {

// Lengths to cut a `size`-byte file to: 0, every `step`-th length and
// size - 1 (the last byte missing), each below `size`.
inline std::vector<size_t> cutLengths(size_t size, size_t step) {
  std::vector<size_t> cuts;
  for (size_t n = 0; n < size; n += step) cuts.push_back(n);
  if (size > 0 && (cuts.empty() || cuts.back() != size - 1)) cuts.push_back(size - 1);
  return cuts;
}

// While it lives, a thread cuts `path` to `shortLength` bytes and writes
// the rest of `bytes` back, again and again; the file is whole again once
// it is destroyed. `path` must hold `bytes` when it starts.
class ShrinkAndGrow {
 public:
  ShrinkAndGrow(const std::string& path, std::string bytes, size_t shortLength)
      : bytes_(std::move(bytes)), short_(shortLength), fd_(::open(path.c_str(), O_WRONLY | O_CLOEXEC)) {
    thread_ = std::thread([this] {
      while (!stop_) {
        if (::ftruncate(fd_, off_t(short_)) != 0) break;
        writeRest();
        ++cycles_;
      }
    });
  }
  ~ShrinkAndGrow() {
    stop_ = true;
    thread_.join();
    writeRest();
    ::close(fd_);
  }
  ShrinkAndGrow(const ShrinkAndGrow&) = delete;
  ShrinkAndGrow& operator=(const ShrinkAndGrow&) = delete;

  bool started() const { return fd_ >= 0; }
  size_t cycles() const { return cycles_; }

 private:
  void writeRest() {
    for (size_t at = short_; at < bytes_.size();) {
      const ssize_t n = ::pwrite(fd_, bytes_.data() + at, bytes_.size() - at, off_t(at));
      if (n <= 0) return;
      at += size_t(n);
    }
  }

  std::string bytes_;
  size_t short_;
  int fd_;
  std::atomic<bool> stop_{false};
  std::atomic<size_t> cycles_{0};
  std::thread thread_;
};

}  // namespace hs::test

#pragma once
// Content hashes: 64-bit XXH3 (xxHash, Debian's libxxhash) over the bytes
// of a value. They answer "did this blob change since the last save" for
// the .hscene file's blobs (meshes, terrain tiles), and are not
// cryptographic. XXH3 hashes at memory speed (over 10 GB/s a core), so a
// 50M-triangle scan hashes in well under a second before a save.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace hs {

uint64_t contentHash(const void* data, size_t bytes, uint64_t seed = 0);

// A hash over several pieces in order (streaming XXH3): the same bytes in
// the same order give the same hash however they were cut.
class ContentHasher {
 public:
  explicit ContentHasher(uint64_t seed = 0);
  ~ContentHasher();
  ContentHasher(const ContentHasher&) = delete;
  ContentHasher& operator=(const ContentHasher&) = delete;

  ContentHasher& bytes(const void* data, size_t n);
  template <class T>
  ContentHasher& value(const T& v) {
    return bytes(&v, sizeof v);
  }
  ContentHasher& text(std::string_view s) {
    value(uint64_t(s.size()));
    return bytes(s.data(), s.size());
  }
  // The element count, then the elements' bytes (so [a][b] and [ab] differ).
  template <class T>
  ContentHasher& array(const std::vector<T>& v) {
    value(uint64_t(v.size()));
    return bytes(v.data(), v.size() * sizeof(T));
  }
  uint64_t digest() const;

 private:
  void* state_;  // XXH3_state_t, kept out of this header
};

// 16 lower-case hex digits, the form hashes take in files ("0f3a...").
std::string toHex(uint64_t h);
// Parses what toHex wrote; false for anything else.
bool fromHex(std::string_view text, uint64_t& out);

}  // namespace hs

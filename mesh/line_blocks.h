#pragma once
// A byte range of a text source, in pieces of about 256 kB that end after a
// line end, each whole in memory: a view into text in memory, or read from
// the file into a buffer a piece at a time. Small pieces stay in the CPU's
// cache between the read that copies them and the parser that reads them
// (a chunk of 16 MB copied whole would be back in main memory by then),
// and a worker holds one piece, not its chunk.
#include <algorithm>
#include <cstring>
#include <string>
#include <string_view>

#include "mesh/byte_source.h"

namespace hs::mesh {

inline constexpr size_t kLineBlockBytes = 256 << 10;

// Calls block(piece) for consecutive pieces of [begin, end): each ends
// after a line end, except the last when `end` is the end of the file and
// the file has none (a line longer than a piece makes the piece longer).
// Stops when block returns false. False with `error` when the file could
// not be read (shrank, I/O error).
template <class Fn>
bool forEachLineBlock(const ByteSource& source, uint64_t begin, uint64_t end, std::string& buffer, std::string& error,
                      Fn&& block) {
  if (const auto text = source.inMemory()) {
    for (uint64_t at = begin; at < end;) {
      uint64_t cut = std::min(end, at + kLineBlockBytes);
      if (cut < end) {
        const void* nl = std::memchr(text->data() + cut, '\n', size_t(end - cut));
        cut = nl ? uint64_t(static_cast<const char*>(nl) - text->data()) + 1 : end;
      }
      if (!block(text->substr(size_t(at), size_t(cut - at)))) return true;
      at = cut;
    }
    return true;
  }
  size_t carry = 0;  // bytes of an unfinished line at the buffer's start
  for (uint64_t at = begin; at < end;) {
    const size_t want = size_t(std::min<uint64_t>(kLineBlockBytes, end - at));
    if (buffer.size() < carry + want) buffer.resize(carry + want);
    if (!source.readInto(at, want, buffer.data() + carry, error)) return false;
    at += want;
    const size_t have = carry + want;
    size_t cut = have;
    if (at < end) {
      const void* nl = memrchr(buffer.data(), '\n', have);
      if (!nl) {  // no line end yet: read more onto it
        carry = have;
        continue;
      }
      cut = size_t(static_cast<const char*>(nl) - buffer.data()) + 1;
    }
    if (!block(std::string_view(buffer.data(), cut))) return true;
    carry = have - cut;
    std::memmove(buffer.data(), buffer.data() + cut, carry);
  }
  return true;
}

}  // namespace hs::mesh

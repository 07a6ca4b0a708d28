// STL checked before Assimp reads it (mesh/declared_counts.h).
#include <cstdint>
#include <cstring>

#include "mesh/declared_counts.h"

namespace hs::mesh {
namespace {

bool isWhite(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// ASCII the way Assimp decides it: starts with "solid" and the first bytes
// are printable text. A binary file whose 80-byte header starts with
// "solid" (some exporters write that) has zeros or floats there.
bool looksAscii(std::string_view head) {
  size_t at = 0;
  while (at < head.size() && isWhite(head[at])) ++at;
  if (head.substr(at, 5) != "solid") return false;
  for (char c : head.substr(0, 512)) {
    const auto u = static_cast<unsigned char>(c);
    if (u > 126 || (u < 32 && !isWhite(c))) return false;
  }
  return true;
}

}  // namespace

bool checkStl(const ByteSource& source, DeclaredCounts& declared, std::string& error) {
  const std::string& path = source.name();
  declared = {};
  std::string buffer;
  std::string_view head;
  if (!source.read(0, 1024, buffer, head, error)) return false;
  uint32_t count = 0;
  if (head.size() >= 84) std::memcpy(&count, head.data() + 80, 4);  // little-endian, as x86 and ARM are
  const uint64_t binarySize = 84 + 50 * uint64_t(count);
  const bool binary = (head.size() >= 84 && binarySize == source.size()) || !looksAscii(head);
  if (binary) {
    if (source.size() < 84) {
      error = path + ": too short for a binary STL (" + std::to_string(source.size()) +
              " bytes; its header alone is 84) and not an ASCII one (no 'solid' line)";
      return false;
    }
    if (binarySize > source.size()) {
      error = path + ": the binary STL's header (byte 80) declares " + std::to_string(count) +
              " triangles, which need " + std::to_string(binarySize) + " bytes, but the file has " +
              std::to_string(source.size()) + " (" + std::to_string((source.size() - 84) / 50) +
              " whole triangles); it is cut short or damaged";
      return false;
    }
    declared.triangles = count;
    declared.by = "binary STL header: " + std::to_string(count) + " triangles";
    return true;
  }

  // ASCII: count the facets, and check that each ends and the solid ends
  // after the last one. Words are compared only by their first letters'
  // worth; a file is read once in 1 MB pieces.
  uint64_t facets = 0, endFacets = 0, lastFacetAt = 0;
  bool endSolidAfterLast = false;
  std::string word;
  uint64_t wordAt = 0;
  auto endWord = [&] {
    if (word == "facet") {
      ++facets;
      lastFacetAt = wordAt;
      endSolidAfterLast = false;
    } else if (word == "endfacet") {
      ++endFacets;
    } else if (word == "endsolid") {
      endSolidAfterLast = facets == endFacets;
    }
    word.clear();
  };
  for (uint64_t at = 0; at < source.size();) {
    std::string_view piece;
    if (!source.read(at, 1 << 20, buffer, piece, error)) return false;
    for (size_t i = 0; i < piece.size(); ++i) {
      const char c = piece[i];
      if (isWhite(c)) {
        if (!word.empty()) endWord();
      } else {
        if (word.empty()) wordAt = at + i;
        if (word.size() < 9) word += c;
      }
    }
    at += piece.size();
  }
  if (!word.empty()) endWord();
  if (facets < endFacets) {
    // A 'facet' keyword itself is damaged: not a cut.
    error = path + ": the ASCII STL is damaged: " + std::to_string(endFacets) + " 'endfacet' but only " +
            std::to_string(facets) + " 'facet' keywords";
    return false;
  }
  if (facets != endFacets || !endSolidAfterLast) {
    error = path + ": the ASCII STL is cut short: " +
            (facets != endFacets ? "facet " + std::to_string(facets) + " (at byte " + std::to_string(lastFacetAt) +
                                       ") has no 'endfacet'"
                                 : std::string("no 'endsolid' after the last facet")) +
            " (" + std::to_string(endFacets) + " complete facets); the file is damaged or truncated";
    return false;
  }
  declared.triangles = size_t(facets);
  declared.by = "ASCII STL: " + std::to_string(facets) + " facets";
  return true;
}

}  // namespace hs::mesh

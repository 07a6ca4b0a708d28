#include "mesh/ply_check.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include "mesh/declared_counts.h"
#include "mesh/ply_body.h"
#include "mesh/ply_header.h"

// The check before Assimp reads a PLY file (`--reader assimp`). It parses
// the header with the own reader's parser (mesh/ply_header.h) and walks the
// body with its cursor (mesh/ply_body.h), so both paths refuse the same
// files with the same messages; what is left here is the walk itself,
// which reads only the list lengths (and strip indices) it needs to count
// triangles and find a body cut short.

namespace hs::mesh {
namespace {

// Triangles a face list of n corners makes (a polygon fan).
uint64_t polygonTriangles(int64_t n) { return n >= 3 ? uint64_t(n - 2) : 0; }

// Triangles of one triangle strip list (-1 restarts a strip). Every
// triangle of the strip counts, joins included: what Assimp's own strip
// reading makes of the list.
struct StripCounter {
  uint64_t triangles = 0, run = 0;
  void add(int64_t index) {
    if (index < 0) {
      run = 0;
      return;
    }
    if (++run >= 3) ++triangles;
  }
};

}  // namespace

bool checkPly(const ByteSource& source, DeclaredCounts& declared, std::string& error) {
  const std::string& file = source.name();
  declared = {};
  // Header: end_header present, keywords, types and counts, every element
  // against the bytes after the header (nothing is allocated for a count).
  ply::Header h;
  if (!ply::readHeader(source, h, error)) return false;
  const bool ascii = h.format == ply::Format::Ascii;
  ply::Body body(source, h.bodyOffset, ascii, h.format == ply::Format::BinaryBigEndian);

  uint64_t faceTriangles = 0, stripTriangles = 0;
  bool haveFaces = false, haveStrips = false;
  for (const ply::Element& e : h.elements) {
    const bool isFace = e.name == "face", isStrip = e.name == "tristrips";
    haveFaces |= isFace;
    haveStrips |= isStrip;
    if (e.properties.empty()) continue;  // rows without data (readHeader bounds their count)
    const bool fixed = std::none_of(e.properties.begin(), e.properties.end(), [](const auto& p) { return p.list; });
    // Binary rows of fixed size: readHeader has checked that they fit.
    if (!ascii && fixed) {
      if (!body.skip(e.count * e.minBytes(false))) {
        error = file + ": in element " + e.name + " (byte " + std::to_string(body.offset()) + "): " + body.error;
        return false;
      }
      continue;
    }
    StripCounter strips;
    for (uint64_t row = 0; row < e.count; ++row) {
      const uint64_t at = body.offset();
      // The same place and wording as the own reader (mesh/ply_reader.cpp).
      auto fail = [&](const std::string& what) {
        error = file + ": in " + e.name + " " + std::to_string(row + 1) + " of " + std::to_string(e.count) +
                " (byte " + std::to_string(at) + "): " + what;
        return false;
      };
      bool firstList = true;
      for (const ply::Property& p : e.properties) {
        double value = 0.0;
        if (!p.list) {
          if (!body.value(p.type, value)) return fail(body.error);
          continue;
        }
        int64_t n = 0;
        if (!body.integer(p.countType, n)) return fail(body.error);
        if (n < 0) return fail("a list of " + std::to_string(n) + " entries");
        if (uint64_t(n) > source.size() - std::min(source.size(), body.offset()))
          return fail("a list of " + std::to_string(n) + " entries runs past the end of the file");
        const bool countStrip = isStrip && firstList;
        if (!ascii && !countStrip) {
          if (!body.skip(uint64_t(n) * uint64_t(ply::typeSize(p.type)))) return fail(body.error);
        } else {
          for (int64_t i = 0; i < n; ++i) {
            int64_t index = 0;
            if (countStrip ? !body.integer(p.type, index) : !body.value(p.type, value)) return fail(body.error);
            if (countStrip) strips.add(index);
          }
        }
        if (countStrip) strips.run = 0;
        if (isFace && firstList) faceTriangles += polygonTriangles(n);
        firstList = false;
      }
    }
    stripTriangles += strips.triangles;
  }
  // Data past the last element: the header declares less than the file
  // holds (a count lowered by hand, or two files joined). Read as declared,
  // and said in the own reader's words.
  if (body.offset() < source.size() && body.hasData())
    declared.warnings.push_back(file + ": " + std::to_string(source.size() - body.offset()) +
                                " bytes of data follow the elements the header declares (from byte " +
                                std::to_string(body.offset()) +
                                "); the rest is not read (the header's counts may be too low)");
  if (haveFaces || haveStrips) {
    declared.triangles = size_t(faceTriangles + stripTriangles);
    declared.by = std::string("PLY ") + (haveFaces ? "face" : "") + (haveFaces && haveStrips ? " and " : "") +
                  (haveStrips ? "tristrips" : "") + " elements";
  }
  return true;
}

bool checkPlyComplete(const std::string& path, std::string& error) {
  ByteSource source;
  if (!source.open(path, error)) return false;
  DeclaredCounts declared;
  return checkPly(source, declared, error);
}

}  // namespace hs::mesh

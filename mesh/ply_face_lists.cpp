#include "mesh/ply_face_lists.h"

#include <algorithm>

#include "core/parallel.h"
#include "mesh/ply_body.h"

namespace hs::mesh::ply {

bool faceListLayout(const Element& e, bool ascii, bool swap, FaceListLayout& layout) {
  if (ascii || e.properties.size() != 1) return false;
  const Property& p = e.properties.front();
  if (!p.list || (p.name != "vertex_indices" && p.name != "vertex_index")) return false;
  if (p.type != Type::Int32 && p.type != Type::UInt32) return false;
  if (p.countType == Type::Float32 || p.countType == Type::Float64) return false;
  layout = {p.countType, p.type, swap};
  return true;
}

void readFaceLists(const FaceListLayout& layout, const char* bytes, size_t size, size_t maxFaces,
                   uint64_t vertexCount, FaceListPiece& piece, std::vector<uint32_t>& triangles) {
  piece.faces = piece.bytes = piece.declaredTriangles = piece.polygons = piece.kept = 0;
  piece.start.clear();
  piece.corners.clear();
  const size_t countBytes = size_t(typeSize(layout.countType));
  // Serial: where each whole face starts (the counts only).
  size_t at = 0;
  while (piece.start.size() < maxFaces && at + countBytes <= size) {
    const double n = decodeValue(layout.countType, bytes + at, layout.swap);
    if (n < 0.0 || at + countBytes + 4 * size_t(n) > size) break;
    piece.start.push_back(uint32_t(at));
    piece.corners.push_back(uint32_t(n));
    at += countBytes + 4 * size_t(n);
  }
  const size_t faces = piece.start.size();
  piece.faces = faces;
  piece.bytes = at;
  if (faces == 0) return;
  // Triangles before each face, as if every face were kept.
  std::vector<size_t> first(faces + 1, 0);
  for (size_t f = 0; f < faces; ++f) first[f + 1] = first[f] + (piece.corners[f] >= 3 ? piece.corners[f] - 2 : 0);
  piece.declaredTriangles = first[faces];
  const size_t base = triangles.size();
  triangles.resize(base + 3 * first[faces]);
  piece.status.assign(faces, FaceStatus::Kept);
  const bool isSigned = layout.indexType == Type::Int32;
  // Parallel: decode, check and fan each face into its own place.
  parallelFor(int64_t(faces), 0, 4096, [&](int64_t lo, int64_t hi) {
    for (int64_t f = lo; f < hi; ++f) {
      const uint32_t n = piece.corners[size_t(f)];
      if (n < 3) {
        piece.status[size_t(f)] = FaceStatus::TooFew;
        continue;
      }
      const char* q = bytes + piece.start[size_t(f)] + countBytes;
      auto index = [&](uint32_t k) {
        uint32_t v;
        std::memcpy(&v, q + 4 * k, 4);
        if (layout.swap) v = __builtin_bswap32(v);
        return isSigned ? int64_t(int32_t(v)) : int64_t(v);
      };
      bool inRange = true;
      for (uint32_t k = 0; k < n; ++k) {
        const int64_t v = index(k);
        inRange &= v >= 0 && v < int64_t(vertexCount);
      }
      if (!inRange) {
        piece.status[size_t(f)] = FaceStatus::OutOfRange;
        continue;
      }
      uint32_t* out = triangles.data() + base + 3 * first[size_t(f)];
      const uint32_t a = uint32_t(index(0));
      for (uint32_t k = 1; k + 1 < n; ++k) {
        *out++ = a;
        *out++ = uint32_t(index(k));
        *out++ = uint32_t(index(k + 1));
      }
    }
  });
  // Squeeze out the dropped faces, in order (rare: most pieces have none).
  size_t write = base;
  bool moved = false;
  for (size_t f = 0; f < faces; ++f) {
    const size_t count = 3 * (first[f + 1] - first[f]);
    if (piece.status[f] != FaceStatus::Kept) {
      moved = true;
      continue;
    }
    piece.polygons += piece.corners[f] > 3;
    if (moved) std::copy_n(triangles.begin() + ptrdiff_t(base + 3 * first[f]), count, triangles.begin() + ptrdiff_t(write));
    write += count;
  }
  triangles.resize(write);
  piece.kept = (write - base) / 3;
}

}  // namespace hs::mesh::ply

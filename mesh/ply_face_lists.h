#pragma once
// Binary PLY faces on every thread (mesh/ply_reader.cpp). A face list's
// length is in its own first bytes, so where a face starts is known only
// after reading every face before it. The reader therefore takes the body
// a piece at a time (4 MB): one serial scan of the piece reads only the
// list counts (one small load per face) to find where each whole face in
// it starts and how many triangles come before it; then the faces are
// decoded, checked and fanned into triangles on every thread, each face
// writing its own triangles at its own place. Faces with too few corners
// or an index out of range are then squeezed out in order, so the result,
// its counts and its messages are those of reading face by face. A face
// that does not fit in a piece, and every other layout (ASCII, texcoord
// lists, texnumber, indices other than 32-bit), are read face by face.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/ply_header.h"

namespace hs::mesh::ply {

// The layout the parallel path reads: an element whose only property is a
// list of 32-bit vertex indices with an integer count.
struct FaceListLayout {
  Type countType = Type::UInt8;
  Type indexType = Type::Int32;
  bool swap = false;  // big-endian file
};
// True (and `layout` set) when `e`, in a binary file, has that layout.
bool faceListLayout(const Element& e, bool ascii, bool swap, FaceListLayout& layout);

enum class FaceStatus : uint8_t { Kept, TooFew, OutOfRange };

struct FaceListPiece {
  size_t faces = 0;                 // whole faces read from the piece
  size_t bytes = 0;                 // bytes they take
  std::vector<uint32_t> start;      // byte of each face in the piece
  std::vector<uint32_t> corners;    // per face: its list length
  std::vector<FaceStatus> status;   // per face
  size_t declaredTriangles = 0;     // n - 2 per face of 3+ corners, dropped ones included
  size_t polygons = 0;              // kept faces of 4+ corners
  size_t kept = 0;                  // triangles appended
};

// Reads the whole faces in bytes[0, size), at most `maxFaces`, appending
// their triangles (fans) to `triangles` (vertex indices, 3 per triangle).
// Stops before a face cut by the piece's end or with a negative count
// (read face by face, which reports it).
void readFaceLists(const FaceListLayout& layout, const char* bytes, size_t size, size_t maxFaces,
                   uint64_t vertexCount, FaceListPiece& piece, std::vector<uint32_t>& triangles);

}  // namespace hs::mesh::ply

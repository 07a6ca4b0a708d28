#pragma once
// What a mesh file declares, read and checked before Assimp sees it.
//
// Assimp 5.2.5 trusts a file's counts: it allocates what a PLY header or a
// GLB chunk length asks for (99999999999999999999 vertices grow the worker
// until it is killed), reads a PLY header with no end forever, and imports
// whatever the data gives without comparing it with what the header said
// (a truncated ASCII STL comes in as 20 of 200 triangles, a PLY header
// claiming 250 faces over 200 invents 50). These checks read the file once,
// in pieces (mesh/byte_source.h), refuse counts the file cannot hold and
// data cut short with the element and byte offset, and return the triangle
// count the file declares, which importMesh compares with what was
// imported (ImportReport::declaredTriangles, ImportOptions::strict).
//
// The own PLY reader of issue 11 plugs in here: it fills the same
// DeclaredCounts from its header and is compared the same way.
#include <cstddef>
#include <string>
#include <vector>

#include "mesh/byte_source.h"

namespace hs::mesh {

struct DeclaredCounts {
  size_t triangles = 0;  // triangles the file's faces / counts / accessors make
  std::string by;        // where that comes from; empty: the format declares nothing we read
  std::vector<std::string> warnings;  // what is read but looks wrong (data past the declared elements)
};

// PLY (mesh/ply_check.cpp): element counts must be whole numbers the file
// can hold; binary bodies are checked for their size, list by list; ASCII
// bodies token by token (a count past the data, a row cut short). Declares
// the triangles of `face` lists (n - 2 per polygon) or of `tristrips`.
bool checkPly(const ByteSource& source, DeclaredCounts& declared, std::string& error);

// STL (mesh/stl_check.cpp): a binary file's triangle count against its size;
// an ASCII file's facets, which must be complete and end with `endsolid`.
bool checkStl(const ByteSource& source, DeclaredCounts& declared, std::string& error);

// glTF 2 (mesh/gltf_check.cpp), `.glb` (binary) or `.gltf`: chunk lengths,
// buffers (external ones must be regular files of the declared length),
// buffer views and accessor counts against the bytes behind them. Declares
// the triangles of every primitive the scene's nodes draw.
bool checkGltf(const ByteSource& source, bool binary, const std::string& baseDir, DeclaredCounts& declared,
               std::string& error);

// By extension (.ply, .stl, .glb, .gltf); other formats pass with nothing
// declared. False with `error` naming the file and place.
bool checkBeforeAssimp(const std::string& path, DeclaredCounts& declared, std::string& error);

}  // namespace hs::mesh

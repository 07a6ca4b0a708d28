#pragma once
// A PLY file checked before Assimp sees it (mesh/declared_counts.h,
// checkPly, does the work). Assimp 5.2.5 loops forever on a PLY whose
// header is cut short (its line reader never reaches `end_header`),
// allocates whatever an element count asks for, and reads a body cut short
// without a word or crashes on it; a scan still being copied looks exactly
// like that.
#include <string>

namespace hs::mesh {

// False with `error` naming the file when the header has no `end_header`
// line, an element count is not a whole number or more than the file can
// hold, or the body is shorter than its elements need: every fixed-size
// property counted, each list's entries by the counts the body gives, an
// ASCII body value by value. The header and body are read by the own PLY
// reader's parser and cursor (mesh/ply_header.h, mesh/ply_body.h), so the
// messages are the own reader's. The file is read once, in 4 MB pieces.
bool checkPlyComplete(const std::string& path, std::string& error);

}  // namespace hs::mesh

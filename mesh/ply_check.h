#pragma once
// A PLY file cut short, checked before Assimp sees it. Assimp 5.2.5 loops
// forever on a PLY whose header is cut short (its line reader never
// reaches `end_header`), and reads a binary body cut short without a word
// or crashes on it; a scan still being copied looks exactly like that.
#include <string>

namespace hs::mesh {

// False with `error` naming the file when the header has no `end_header`
// line, or (binary PLY) the body is shorter than its elements need: every
// fixed-size property counted, and each list's entries by the counts the
// body gives. An ASCII body is not checked here (Assimp refuses one with
// too few values). The file is read once, in 1 MB pieces.
bool checkPlyComplete(const std::string& path, std::string& error);

}  // namespace hs::mesh

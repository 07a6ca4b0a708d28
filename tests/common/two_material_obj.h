#pragma once
// A two-material OBJ for the suites that export what the import kept: two
// quads side by side, one material each, the MTL beside it.
#include <string>

#include "file_bytes.h"

namespace hs::test {

// Writes <dir>/two.obj and <dir>/two.mtl; returns the OBJ's path.
inline std::string writeTwoMaterialObj(const std::string& dir) {
  writeFile(dir + "/two.mtl", "newmtl rock\nKd 0.5 0.4 0.3\nnewmtl moss\nKd 0.1 0.6 0.2\n");
  writeFile(dir + "/two.obj",
            "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
            "usemtl rock\nf 1 2 3\nf 1 3 4\nusemtl moss\nf 2 5 6\nf 2 6 3\n");
  return dir + "/two.obj";
}

}  // namespace hs::test

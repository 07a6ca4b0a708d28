#pragma once
// Whole-file reads and writes for suites that build, compare or damage files.
#include <fstream>
#include <sstream>
#include <string>

namespace hs::test {

// The file's bytes; empty if it cannot be read.
inline std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Replaces the file's content with `bytes`.
inline void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), std::streamsize(bytes.size()));
}

}  // namespace hs::test

#include "scene/ocio_cache.h"

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <fstream>

namespace hs::scene {

namespace fs = std::filesystem;

fs::path userCacheFolder(const std::string& name) {
  std::error_code ec;
  return fs::temp_directory_path(ec) / (name + "-" + std::to_string(getuid()));
}

bool writeCacheFile(const fs::path& file, const std::string& bytes, std::string& error) {
  std::error_code ec;
  if (fs::exists(file, ec) && fs::file_size(file, ec) == bytes.size()) return true;
  fs::create_directories(file.parent_path(), ec);
  static std::atomic<int> counter{0};
  const fs::path part = file.string() + ".part" + std::to_string(getpid()) + "_" + std::to_string(counter++);
  {
    std::ofstream out(part, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) {
      error = "cannot write " + part.string();
      fs::remove(part, ec);
      return false;
    }
  }
  fs::rename(part, file, ec);
  if (ec) {
    error = "cannot write " + file.string() + ": " + ec.message();
    fs::remove(part, ec);
    return false;
  }
  return true;
}

std::string ocioMessage(std::string message, const std::string& cachePath, const std::string& name) {
  for (size_t at; !cachePath.empty() && (at = message.find(cachePath)) != std::string::npos;)
    message.replace(at, cachePath.size(), name);
  std::string oneLine;  // OpenColorIO's messages run over several lines: kept whole, on one
  for (char c : message)
    if (!std::isspace(static_cast<unsigned char>(c))) oneLine += c;
    else if (!oneLine.empty() && oneLine.back() != ' ') oneLine += ' ';
  return oneLine;
}

}  // namespace hs::scene

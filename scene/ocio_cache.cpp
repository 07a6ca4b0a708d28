#include "scene/ocio_cache.h"

#include <unistd.h>

#include <cctype>
#include <fstream>

#include "core/scratch_files.h"

namespace hs::scene {

namespace fs = std::filesystem;

fs::path userCacheFolder(const std::string& name) {
  std::error_code ec;
  return fs::temp_directory_path(ec) / (name + "-" + std::to_string(getuid()));
}

bool writeCacheFile(const fs::path& file, const std::string& bytes, std::string& error) {
  // A writer killed between writing and renaming leaves its part behind
  // (as large as the file: a LUT can be tens of MB): this machine's whose
  // process is gone are removed by the next writer of the same file.
  const std::string partPrefix = file.filename().string() + ".part-";
  sweepStaleScratch(file.parent_path(), partPrefix);
  std::error_code ec;
  if (fs::exists(file, ec) && fs::file_size(file, ec) == bytes.size()) return true;
  fs::create_directories(file.parent_path(), ec);
  const fs::path part = file.parent_path() / scratchName(partPrefix);
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

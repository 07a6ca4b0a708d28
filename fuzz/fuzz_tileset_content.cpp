// A 3D Tiles tile's content as mesh/tileset_reader.h reads it: the input is
// the content file (b3dm with its feature table and RTC_CENTER, cmpt and
// the tiles inside it, glb, glTF or external tileset JSON, pnts and the
// other formats it names), behind a fixed tileset.json. The reader takes
// files, so each input is written to a directory of this process's own.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_target.h"
#include "mesh/tileset_reader.h"

namespace {

const std::filesystem::path& workDir() {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("hs-fuzz-tileset-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::ofstream(d / "tileset.json")
        << R"({"asset":{"version":"1.1"},"geometricError":10,"root":{"boundingVolume":{"sphere":[0,0,0,100]},)"
           R"("geometricError":1,"refine":"REPLACE","content":{"uri":"tile.bin"}}})";
    return d;
  }();
  return dir;
}

struct RemoveAtExit {
  ~RemoveAtExit() {
    std::error_code ec;
    std::filesystem::remove_all(workDir(), ec);
  }
} removeAtExit;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::ofstream(workDir() / "tile.bin", std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  hs::mesh::Tileset tileset;
  std::string error;
  hs::mesh::readTileset((workDir() / "tileset.json").string(), tileset, error);
  return 0;
}

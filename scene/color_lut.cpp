#include "scene/color_lut.h"


#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/content_hash.h"
#include "scene/edit.h"
#include "scene/lut_processor.h"
#include "scene/ocio_cache.h"

namespace OCIO = OCIO_NAMESPACE;

namespace hs::scene {
namespace {

std::string extensionOf(const std::string& fileName) {
  const std::string ext = std::filesystem::path(fileName).extension().string();
  return ext.empty() ? std::string() : ext.substr(1);
}

// A text format holds its numbers as words; one that reads as a number but
// is not finite ("nan", "inf", "1e999") would reach the GPU as NaN.
std::string nonFiniteNumber(const std::string& where, const std::string& bytes) {
  if (bytes.find('\0') != std::string::npos) return "";  // a binary format: the lattice check covers it
  std::istringstream in(bytes);
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream words(line);
    std::string w;
    while (words >> w) {
      char* end = nullptr;
      const double v = std::strtod(w.c_str(), &end);
      if (end == w.c_str() + w.size() && !std::isfinite(v))
        return where + ":" + std::to_string(number) + ": '" + w + "' is not a finite number";
    }
  }
  return "";
}

}  // namespace

std::string lutBlobKey(uint64_t hash) { return "lut/" + toHex(hash); }

std::vector<std::string> lutFileExtensions() {
  std::vector<std::string> out;
  for (int i = 0; i < OCIO::FileTransform::GetNumFormats(); ++i) {
    const std::string ext = OCIO::FileTransform::GetFormatExtensionByIndex(i);
    if (std::find(out.begin(), out.end(), ext) == out.end()) out.push_back(ext);
  }
  return out;
}

std::string lutCacheFile(const LutData& lut, std::string& error) {
  if (!lut.bytes) {
    error = lut.fileName + ": the LUT's data is not loaded";
    return {};
  }
  const std::string ext = extensionOf(lut.fileName);
  const std::filesystem::path file =
      userCacheFolder("hybridscape-luts") / (toHex(lut.contentHash) + (ext.empty() ? "" : "." + ext));
  std::string why;
  if (!writeCacheFile(file, *lut.bytes, why)) {
    error = lut.fileName + ": cannot write the LUT for OpenColorIO: " + why;
    return {};
  }
  return file.string();
}

OCIO::ConstProcessorRcPtr lutProcessor(const LutData& lut, std::string& error) {
  const std::string path = lutCacheFile(lut, error);
  if (path.empty()) return {};
  try {
    OCIO::FileTransformRcPtr file = OCIO::FileTransform::Create();
    file->setSrc(path.c_str());
    file->setInterpolation(OCIO::INTERP_BEST);
    file->setDirection(OCIO::TRANSFORM_DIR_FORWARD);
    return OCIO::Config::CreateRaw()->getProcessor(file);
  } catch (const std::exception& e) {
    error = ocioMessage(e.what(), path, lut.fileName);
    return {};
  }
}

std::string lutProblem(const std::string& where, const LutData& lut) {
  if (!lut.bytes) return where + ": the LUT's data is not loaded";
  const std::string& bytes = *lut.bytes;
  if (bytes.empty()) return where + ": the file is empty";
  if (bytes.size() > kMaxLutFileBytes)
    return where + ": " + std::to_string(bytes.size() >> 20) + " MB, larger than the " +
           std::to_string(kMaxLutFileBytes >> 20) + " MB a LUT may have";
  if (std::string p = nonFiniteNumber(where, bytes); !p.empty()) return p;
  std::string error;
  const OCIO::ConstProcessorRcPtr processor = lutProcessor(lut, error);
  if (!processor) {
    // OpenColorIO says per format it tried why (with the line for text
    // formats): ocioMessage keeps it whole, on one line.
    return where + ": OpenColorIO cannot read it as a LUT: " + error;
  }
  try {
    const OCIO::ConstCPUProcessorRcPtr cpu = processor->getDefaultCPUProcessor();
    constexpr int n = 17;
    for (int b = 0; b < n; ++b)
      for (int g = 0; g < n; ++g)
        for (int r = 0; r < n; ++r) {
          float rgb[3] = {float(r) / (n - 1), float(g) / (n - 1), float(b) / (n - 1)};
          cpu->applyRGB(rgb);
          if (!std::isfinite(rgb[0]) || !std::isfinite(rgb[1]) || !std::isfinite(rgb[2]))
            return where + ": gives a non-finite colour for the input (" + std::to_string(float(r) / (n - 1)) +
                   ", " + std::to_string(float(g) / (n - 1)) + ", " + std::to_string(float(b) / (n - 1)) + ")";
        }
  } catch (const std::exception& e) {
    return where + ": OpenColorIO cannot apply it: " + e.what();
  }
  return "";
}

std::optional<LutData> readLutFile(const std::string& path, std::string& error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    error = path + ": a folder, not a LUT file";
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot open it";
    return std::nullopt;
  }
  const uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxLutFileBytes) {
    error = path + ": " + std::to_string(size >> 20) + " MB, larger than the " + std::to_string(kMaxLutFileBytes >> 20) +
            " MB a LUT may have";
    return std::nullopt;
  }
  std::ostringstream read;
  read << in.rdbuf();
  auto bytes = std::make_shared<const std::string>(std::move(read).str());
  const uint64_t hash = contentHash(bytes->data(), bytes->size());
  LutData lut{fs::path(path).filename().string(), std::move(bytes), hash};
  if (std::string p = lutProblem(path, lut); !p.empty()) {
    error = p;
    return std::nullopt;
  }
  return lut;
}

const OperationDecl& lutImportOperation() {
  static const OperationDecl op{
      .name = "lut import",
      .summary = "grade the scene with a LUT file (stored in the scene)",
      .usage = "<lut-file> <scene.hscene>",
      .description = "Reads a colour look-up table with OpenColorIO (.cube, .3dl, .spi3d, .spi1d, .csp, .clf and "
                     "the other formats it reads), stores its bytes in the scene (a render node needs no copy of "
                     "the file) and turns settings.post.lut.enabled on. The LUT maps sRGB-encoded display values "
                     "after the tone map and the grade (docs/rendering.md, \"Post-processing\"). A scene holds "
                     "one LUT: importing another replaces it.",
      .notes = "Mix it in with: hybridscape-cli set settings.post.lut.intensity 0.5 scene.hscene",
      .positionals = {{.name = "lut-file", .help = "the LUT file"}, {.name = "scene.hscene", .help = "the scene file"}},
  };
  return op;
}

const OperationDecl& lutClearOperation() {
  static const OperationDecl op{
      .name = "lut clear",
      .summary = "remove the scene's LUT",
      .usage = "<scene.hscene>",
      .description = "Removes the stored LUT and turns settings.post.lut.enabled off.",
      .positionals = {{.name = "scene.hscene", .help = "the scene file"}},
  };
  return op;
}

namespace ops {
bool setLut(Document& doc, const LutData& lut) {
  Edit e(doc, lut.empty() ? QString("Remove LUT") : QString("Import LUT %1").arg(QString::fromStdString(lut.fileName)));
  e.settings().post.lut = lut;
  e.settings().post.lutEnabled = !lut.empty();
  return e.commit();
}
}  // namespace ops

}  // namespace hs::scene

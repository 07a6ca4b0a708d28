#pragma once
// Golden-image comparison with an explicit tolerance: a pixel "differs" when
// any channel differs by more than `channelTolerance`; the comparison passes
// when the largest channel difference is at most `maxChannelDiff` and the
// share of differing pixels is at most `maxDifferingShare`.
//
// Goldens are PNG files under tests/<area>/golden/. Set HS_UPDATE_GOLDEN=1 to
// (re)write them from the current output, then look at them before committing.
// On a mismatch the actual image and an amplified difference image are
// written to the build tree (the failure message says where).
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

namespace hs::test {

struct Rgba8Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // top row first
};

struct CompareResult {
  bool sizeMatches = false;
  int maxChannelDiff = 0;
  double differingShare = 0.0;
  std::string summary() const {
    if (!sizeMatches) return "image sizes differ";
    return "max channel difference " + std::to_string(maxChannelDiff) + ", " +
           std::to_string(differingShare * 100.0) + "% of pixels differ";
  }
};

inline CompareResult compareImages(const Rgba8Image& a, const Rgba8Image& b, int channelTolerance) {
  CompareResult r;
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size()) return r;
  r.sizeMatches = true;
  size_t differing = 0;
  const size_t n = size_t(a.width) * size_t(a.height);
  for (size_t i = 0; i < n; ++i) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a.rgba[i * 4 + c]) - int(b.rgba[i * 4 + c])));
    r.maxChannelDiff = std::max(r.maxChannelDiff, worst);
    if (worst > channelTolerance) ++differing;
  }
  r.differingShare = n ? double(differing) / double(n) : 0.0;
  return r;
}

// Written as RGB: rendered frames are opaque, and PNG's unassociated alpha
// would make OpenImageIO rescale colours on write and read.
inline bool writePng(const std::string& path, const Rgba8Image& img) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return false;
  std::vector<uint8_t> rgb(size_t(img.width) * size_t(img.height) * 3);
  for (size_t i = 0; i < rgb.size() / 3; ++i)
    for (int c = 0; c < 3; ++c) rgb[i * 3 + size_t(c)] = img.rgba[i * 4 + size_t(c)];
  OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
  return out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) && out->close();
}

inline bool readPng(const std::string& path, Rgba8Image& img) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return false;
  const OIIO::ImageSpec& spec = in->spec();
  img.width = spec.width;
  img.height = spec.height;
  img.rgba.assign(size_t(spec.width) * size_t(spec.height) * 4, 255);
  // Read as RGBA whatever the file has (goldens are RGBA, but be lenient).
  std::vector<uint8_t> tmp(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, tmp.data())) return false;
  for (size_t i = 0; i < size_t(spec.width) * size_t(spec.height); ++i)
    for (int c = 0; c < std::min(spec.nchannels, 4); ++c) img.rgba[i * 4 + size_t(c)] = tmp[i * size_t(spec.nchannels) + size_t(c)];
  return true;
}

struct GoldenTolerance {
  int maxChannelDiff = 40;         // no pixel may be off by more than this
  int channelTolerance = 6;        // a pixel counts as differing above this
  double maxDifferingShare = 0.005;
};

// Compares `actual` with the golden `goldenDir/name.png`. Returns an empty
// string on success, else a message naming the files to look at.
inline std::string checkGolden(const std::string& goldenDir, const std::string& outDir, const std::string& name,
                               const Rgba8Image& actual, const GoldenTolerance& tol = {}) {
  const std::string golden = goldenDir + "/" + name + ".png";
  if (std::getenv("HS_UPDATE_GOLDEN")) {
    std::filesystem::create_directories(goldenDir);
    return writePng(golden, actual) ? std::string() : "cannot write golden " + golden;
  }
  Rgba8Image expected;
  if (!readPng(golden, expected)) return "golden image missing: " + golden + " (run with HS_UPDATE_GOLDEN=1 to create it)";
  const CompareResult r = compareImages(actual, expected, tol.channelTolerance);
  if (r.sizeMatches && r.maxChannelDiff <= tol.maxChannelDiff && r.differingShare <= tol.maxDifferingShare) return {};
  std::filesystem::create_directories(outDir);
  const std::string actualPath = outDir + "/" + name + ".actual.png";
  writePng(actualPath, actual);
  if (r.sizeMatches) {
    Rgba8Image diff = actual;
    for (size_t i = 0; i < diff.rgba.size(); i += 4)
      for (int c = 0; c < 3; ++c)
        diff.rgba[i + size_t(c)] = uint8_t(std::min(255, 8 * std::abs(int(actual.rgba[i + size_t(c)]) - int(expected.rgba[i + size_t(c)]))));
    writePng(outDir + "/" + name + ".diff.png", diff);
  }
  return name + ": " + r.summary() + " (tolerance: max " + std::to_string(tol.maxChannelDiff) + ", " +
         std::to_string(tol.maxDifferingShare * 100.0) + "% over " + std::to_string(tol.channelTolerance) +
         "); actual image: " + actualPath;
}

}  // namespace hs::test

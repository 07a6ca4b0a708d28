#pragma once
// The 8-bit channels of an image file as OpenImageIO reads it (any format,
// all its channels, top row first): what the CLI tests compare frames by.
// Empty when the file cannot be read.
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace hs::test {

inline std::vector<unsigned char> filePixels(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<unsigned char> out(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, out.data())) return {};
  return out;
}

}  // namespace hs::test

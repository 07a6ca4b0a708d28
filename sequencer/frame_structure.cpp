#include "sequencer/frame_structure.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>

#include <zlib.h>

#include "sequencer/image_writer.h"

namespace hs::sequencer {

namespace {

uint32_t bigEndian32(const unsigned char* p) {
  return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}

// Walks the chunks (PNG spec, section 5.3): 4-byte length, 4-byte type,
// data, CRC-32 of type and data. Hand-written because libpng would inflate
// every IDAT to get to IEND; this only runs zlib's crc32 over the bytes.
std::string pngProblem(const std::string& bytes) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  const size_t size = bytes.size();
  if (size < 8 || std::memcmp(b, kSignature, 8) != 0) return "not a PNG file (no PNG signature)";
  size_t at = 8;
  while (true) {
    if (size - at < 12)
      return "cut short at byte " + std::to_string(size) + " (a chunk header needs 12 bytes at " + std::to_string(at) +
             "; no IEND)";
    const uint32_t length = bigEndian32(b + at);
    const std::string type(reinterpret_cast<const char*>(b + at + 4), 4);
    if (uint64_t(length) + 12 > uint64_t(size - at))
      return "cut short: chunk " + type + " at byte " + std::to_string(at) + " declares " + std::to_string(length) +
             " bytes, the file ends after " + std::to_string(size - at - 8);
    const uint32_t stored = bigEndian32(b + at + 8 + length);
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), b + at + 4, uInt(length) + 4);
    if (uint32_t(crc) != stored) return "chunk " + type + " at byte " + std::to_string(at) + " fails its CRC";
    if (type == "IEND") return {};
    at += size_t(length) + 12;
  }
}

// JPEG: SOI (FF D8) first and EOI (FF D9) last. libjpeg decodes a file cut
// short into grey with a warning only, so the end marker is what tells.
std::string jpegProblem(const std::string& bytes) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  const size_t n = bytes.size();
  if (n < 4 || b[0] != 0xFF || b[1] != 0xD8) return "not a JPEG file (no SOI marker)";
  if (b[n - 2] != 0xFF || b[n - 1] != 0xD9) return "cut short (no EOI marker at the end of its " + std::to_string(n) + " bytes)";
  return {};
}

}  // namespace

bool hasStructureCheck(const std::string& path) {
  const auto format = imageFormatFromPath(path);
  return format && (*format == ImageFormat::Png || *format == ImageFormat::Jpeg);
}

std::string frameStructureProblem(const std::string& path) {
  const auto format = imageFormatFromPath(path);
  if (!format || (*format != ImageFormat::Png && *format != ImageFormat::Jpeg)) return {};
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return "cannot be read";
  std::string bytes(size_t(std::max<std::streamoff>(0, in.tellg())), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), std::streamsize(bytes.size()))) return "cannot be read to its end";
  return *format == ImageFormat::Png ? pngProblem(bytes) : jpegProblem(bytes);
}

}  // namespace hs::sequencer

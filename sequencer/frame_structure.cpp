#include "sequencer/frame_structure.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

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

uint32_t little32(const unsigned char* p) {
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
uint64_t little64(const unsigned char* p) { return uint64_t(little32(p)) | (uint64_t(little32(p + 4)) << 32); }

// OpenEXR, single-part scanline files (what the export writes; the
// layout is "OpenEXR File Layout" in the OpenEXR documentation): magic,
// version, attributes up to an empty name, then one 64-bit offset per chunk
// and each chunk's y and byte count. Every chunk must lie within the file.
// A writer that stopped leaves offsets of 0 or past the end. Tiled, deep and
// multi-part files return `unknown` (then they are decoded). Hand-written
// because OpenEXR's headers are not installed (OpenImageIO hides them) and
// the walk needs no pixel data.
std::string exrProblem(const std::string& bytes, bool& unknown) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  const size_t n = bytes.size();
  if (n < 8 || little32(b) != 20000630u) return "not an OpenEXR file (no magic number)";
  const uint32_t flags = little32(b + 4);
  if (flags & (0x200u | 0x800u | 0x1000u)) {  // tiled, deep, multi-part
    unknown = true;
    return {};
  }
  size_t at = 8;
  int32_t yMin = 0, yMax = -1;
  int compression = -1;
  while (true) {
    if (at >= n) return "cut short inside its header";
    if (b[at] == 0) {  // the empty name ending the header
      ++at;
      break;
    }
    const void* nameEnd = std::memchr(b + at, 0, n - at);
    if (!nameEnd) return "cut short inside its header";
    const std::string name(reinterpret_cast<const char*>(b + at));
    at = size_t(static_cast<const unsigned char*>(nameEnd) - b) + 1;
    const void* typeEnd = at < n ? std::memchr(b + at, 0, n - at) : nullptr;
    if (!typeEnd) return "cut short inside its header";
    at = size_t(static_cast<const unsigned char*>(typeEnd) - b) + 1;
    if (n - at < 4) return "cut short inside its header";
    const uint32_t size = little32(b + at);
    at += 4;
    if (size > n - at) return "cut short inside its header (attribute " + name + ")";
    if (name == "dataWindow" && size == 16) {
      yMin = int32_t(little32(b + at + 4));
      yMax = int32_t(little32(b + at + 12));
    } else if (name == "compression" && size == 1) {
      compression = b[at];
    }
    at += size;
  }
  static const int kLinesPerChunk[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  if (compression < 0 || compression > 9 || yMax < yMin) {
    unknown = true;  // a header this walk does not know: let the decoder judge
    return {};
  }
  const uint64_t lines = uint64_t(int64_t(yMax) - int64_t(yMin) + 1);
  const uint64_t chunks = (lines + uint64_t(kLinesPerChunk[compression]) - 1) / uint64_t(kLinesPerChunk[compression]);
  if (chunks > (n - at) / 8) return "cut short inside its chunk offset table";
  for (uint64_t c = 0; c < chunks; ++c) {
    const uint64_t offset = little64(b + at + 8 * c);
    if (offset < at + 8 * chunks || offset > n || n - offset < 8)
      return "cut short: chunk " + std::to_string(c) + " of " + std::to_string(chunks) + " is not in the file";
    const uint32_t size = little32(b + offset + 4);
    if (size > n - offset - 8)
      return "cut short: chunk " + std::to_string(c) + " of " + std::to_string(chunks) + " ends past the file's end";
  }
  return {};
}

// TIFF (TIFF 6.0, section 2): the first image's strip or tile offsets and
// byte counts must all lie within the file. Hand-written because libtiff
// reports through process-global handlers (frames are checked on several
// threads) and this needs only the one table. BigTIFF returns `unknown`.
std::string tiffProblem(const std::string& bytes, bool& unknown) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  const size_t n = bytes.size();
  if (n < 8 || !((b[0] == 'I' && b[1] == 'I') || (b[0] == 'M' && b[1] == 'M'))) return "not a TIFF file";
  const bool le = b[0] == 'I';
  auto u16 = [&](size_t at) { return le ? uint32_t(b[at]) | (uint32_t(b[at + 1]) << 8) : (uint32_t(b[at]) << 8) | b[at + 1]; };
  auto u32 = [&](size_t at) { return le ? little32(b + at) : bigEndian32(b + at); };
  if (u16(2) != 42) {
    unknown = true;  // BigTIFF (43) or something else: decode it
    return {};
  }
  const size_t ifd = u32(4);
  if (ifd > n || n - ifd < 2) return "cut short: its first directory is not in the file";
  const size_t entries = u16(ifd);
  if ((n - ifd - 2) / 12 < entries) return "cut short inside its first directory";
  // One list of values (SHORT or LONG) of a tag, or nullopt if absent.
  auto values = [&](uint32_t tag, std::vector<uint64_t>& out, std::string& problem) {
    for (size_t e = 0; e < entries; ++e) {
      const size_t at = ifd + 2 + 12 * e;
      if (u16(at) != tag) continue;
      const uint32_t type = u16(at + 2), count = u32(at + 4);
      const size_t width = type == 3 ? 2 : type == 4 ? 4 : 0;
      if (!width) {
        problem = "tag " + std::to_string(tag) + " has type " + std::to_string(type);
        return true;
      }
      size_t where = at + 8;
      if (uint64_t(count) * width > 4) {
        where = u32(at + 8);
        if (where > n || (n - where) / width < count) {
          problem = "cut short: the table of tag " + std::to_string(tag) + " is not in the file";
          return true;
        }
      }
      for (uint32_t i = 0; i < count; ++i) out.push_back(width == 2 ? u16(where + 2 * i) : u32(where + 4 * i));
      return true;
    }
    return false;
  };
  std::vector<uint64_t> offsets, counts;
  std::string problem;
  const bool strips = values(273, offsets, problem);
  if (!problem.empty()) return problem;
  if (!(strips ? values(279, counts, problem) : (values(324, offsets, problem) && values(325, counts, problem))))
    return problem.empty() ? "no strip or tile table" : problem;
  if (!problem.empty()) return problem;
  if (offsets.size() != counts.size() || offsets.empty()) return "its offset and byte-count tables differ in length";
  for (size_t i = 0; i < offsets.size(); ++i)
    if (offsets[i] > n || counts[i] > n - offsets[i])
      return "cut short: " + std::string(strips ? "strip " : "tile ") + std::to_string(i) + " of " +
             std::to_string(offsets.size()) + " ends past the file's end";
  return {};
}

}  // namespace

std::string frameStructureProblem(const std::string& path, bool& unknown) {
  unknown = false;
  const auto format = imageFormatFromPath(path);
  if (!format) {
    unknown = true;
    return {};
  }
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return "cannot be read";
  std::string bytes(size_t(std::max<std::streamoff>(0, in.tellg())), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), std::streamsize(bytes.size()))) return "cannot be read to its end";
  switch (*format) {
    case ImageFormat::Png: return pngProblem(bytes);
    case ImageFormat::Jpeg: return jpegProblem(bytes);
    case ImageFormat::Exr: return exrProblem(bytes, unknown);
    case ImageFormat::Tiff: return tiffProblem(bytes, unknown);
  }
  unknown = true;
  return {};
}

}  // namespace hs::sequencer

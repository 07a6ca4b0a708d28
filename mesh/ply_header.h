#pragma once
// The header of a PLY file (Turk's format, as MeshLab, Metashape,
// RealityCapture, OpenDroneMap and CloudCompare write it): the format
// (ASCII, binary little- or big-endian), the elements in order with their
// properties (scalars of eight types, or lists with a count type), and the
// comments that name texture files (`comment TextureFile name`).
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/byte_source.h"

namespace hs::mesh::ply {

enum class Type : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
int typeSize(Type t);

struct Property {
  std::string name;
  Type type = Type::Float32;  // a list's item type
  bool list = false;
  Type countType = Type::UInt8;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  int line = 0;  // where the header declares it
  // Bytes one element needs at least: fixed properties, plus each list's
  // count (binary); one character and a separator per property (ASCII).
  uint64_t minBytes(bool ascii) const;
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::vector<std::string> textureFiles;  // `comment TextureFile ...`, in order
  uint64_t bodyOffset = 0;                // first byte after `end_header\n`
};

// Reads and checks the header of `source` (at most 1 MB of it): a file
// without `end_header`, an unknown format, type or keyword, a count that is
// not a whole number or does not fit, or elements that need more bytes than
// the file has after its header are refused with `error` naming the file,
// the line and what is wrong, before anything is allocated for them.
bool readHeader(const ByteSource& source, Header& header, std::string& error);

}  // namespace hs::mesh::ply

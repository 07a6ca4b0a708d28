#include "mesh/ply_header.h"

#include <charconv>
#include <sstream>

namespace hs::mesh::ply {
namespace {

constexpr size_t kMaxHeader = 1 << 20;

bool parseType(const std::string& s, Type& t) {
  static const std::pair<const char*, Type> kNames[] = {
      {"char", Type::Int8},     {"int8", Type::Int8},       {"uchar", Type::UInt8},   {"uint8", Type::UInt8},
      {"short", Type::Int16},   {"int16", Type::Int16},     {"ushort", Type::UInt16}, {"uint16", Type::UInt16},
      {"int", Type::Int32},     {"int32", Type::Int32},     {"uint", Type::UInt32},   {"uint32", Type::UInt32},
      {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64}};
  for (const auto& [name, type] : kNames)
    if (s == name) {
      t = type;
      return true;
    }
  return false;
}

}  // namespace

int typeSize(Type t) {
  switch (t) {
    case Type::Int8: case Type::UInt8: return 1;
    case Type::Int16: case Type::UInt16: return 2;
    case Type::Int32: case Type::UInt32: case Type::Float32: return 4;
    case Type::Float64: return 8;
  }
  return 0;
}

uint64_t Element::minBytes(bool ascii) const {
  uint64_t n = 0;
  for (const Property& p : properties) n += ascii ? 2 : uint64_t(typeSize(p.list ? p.countType : p.type));
  return n;
}

bool readHeader(const ByteSource& source, Header& header, std::string& error) {
  const std::string& file = source.name();
  std::string buffer;
  std::string_view text;
  if (!source.read(0, size_t(std::min<uint64_t>(source.size(), kMaxHeader)), buffer, text, error)) return false;
  const size_t end = text.find("end_header");
  size_t bodyStart = std::string_view::npos;
  if (end != std::string_view::npos) {
    // end_header, then \n (or \r\n): the body starts after the newline.
    size_t p = end + 10;
    while (p < text.size() && text[p] == '\r') ++p;
    if (p < text.size() && text[p] == '\n') bodyStart = p + 1;
    else if (p == text.size() && p == source.size()) bodyStart = p;  // nothing after it: no body
  }
  if (bodyStart == std::string_view::npos) {
    error = file + ": the PLY header has no end_header line" +
            (source.size() > kMaxHeader ? " in its first 1 MB" : " (the file is cut short, or not a PLY file)");
    return false;
  }
  std::istringstream lines{std::string(text.substr(0, end))};
  std::string line;
  int number = 0;
  bool sawFormat = false;
  while (std::getline(lines, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    auto fail = [&](const std::string& what) {
      error = file + ":" + std::to_string(number) + ": PLY header: " + what;
      return false;
    };
    if (number == 1) {
      if (key != "ply") return fail("the file does not start with 'ply'; it is not a PLY file");
      continue;
    }
    if (key.empty() || key == "comment" || key == "obj_info") {
      if (key == "comment") {
        std::string word;
        words >> word;
        if (word == "TextureFile") {
          std::string name;
          std::getline(words >> std::ws, name);
          if (!name.empty()) header.textureFiles.push_back(name);
        }
      }
      continue;
    }
    if (key == "format") {
      std::string format, version;
      words >> format >> version;
      if (format == "ascii") header.format = Format::Ascii;
      else if (format == "binary_little_endian") header.format = Format::BinaryLittleEndian;
      else if (format == "binary_big_endian") header.format = Format::BinaryBigEndian;
      else return fail("unknown format '" + format + "' (ascii, binary_little_endian or binary_big_endian)");
      if (version != "1.0") return fail("format version '" + version + "' (only 1.0 exists)");
      sawFormat = true;
    } else if (key == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      const auto r = std::from_chars(count.data(), count.data() + count.size(), e.count);
      if (e.name.empty()) return fail("an element without a name");
      if (r.ec == std::errc::result_out_of_range)
        return fail("element " + e.name + ": the count '" + count + "' is too large (more than 2^64)");
      if (r.ec != std::errc() || r.ptr != count.data() + count.size())
        return fail("element " + e.name + ": the count '" + count + "' is not a whole number");
      e.line = number;
      header.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (header.elements.empty()) return fail("a property before any element");
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType;
        if (!parseType(countType, p.countType) || !parseType(itemType, p.type))
          return fail("list property types '" + countType + " " + itemType + "' are not PLY types");
        if (p.countType == Type::Float32 || p.countType == Type::Float64)
          return fail("a list's count type must be an integer type, not '" + countType + "'");
        p.list = true;
      } else if (!parseType(type, p.type)) {
        return fail("unknown property type '" + type + "'");
      }
      words >> p.name;
      if (p.name.empty()) return fail("a property without a name");
      header.elements.back().properties.push_back(std::move(p));
    } else {
      return fail("unknown keyword '" + key + "'");
    }
  }
  if (!sawFormat) {
    error = file + ": the PLY header has no format line";
    return false;
  }
  header.bodyOffset = bodyStart;
  // Counts against the bytes there are, before anything is allocated.
  const uint64_t body = source.size() - bodyStart;
  const bool ascii = header.format == Format::Ascii;
  uint64_t need = 0;
  for (const Element& e : header.elements) {
    const uint64_t each = e.minBytes(ascii), left = body - std::min(need, body);
    const std::string place = file + ":" + std::to_string(e.line) + ": PLY header: element " + e.name + " declares " +
                              std::to_string(e.count) + " rows";
    // Rows without properties hold no data; more of them than the file has
    // bytes is not a real file (and reading them would loop for ever).
    if (each == 0 && e.count > body) {
      error = place + " without properties, more than the " + std::to_string(body) + " bytes after the header";
      return false;
    }
    if (each > 0 && e.count > left / each) {
      error = place + ", which need at least " +
              (e.count > UINT64_MAX / each ? std::string("2^64") : std::to_string(e.count * each)) +
              " bytes, but only " + std::to_string(left) +
              " bytes follow the header and the elements before it (truncated, or a wrong count)";
      return false;
    }
    need += e.count * each;
  }
  return true;
}

}  // namespace hs::mesh::ply

#include "mesh/ply_check.h"

#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

#include "mesh/byte_source.h"

namespace hs::mesh {
namespace {

// Size in bytes of a PLY scalar type name; 0 if it is not one.
int scalarSize(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

struct Property {
  int size = 0;       // a scalar's size, or a list entry's
  int countSize = 0;  // a list's count type size; 0 for a scalar
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

// Reads the body sequentially through a 1 MB window.
class BodyReader {
 public:
  BodyReader(const ByteSource& source, uint64_t at) : source_(source), at_(at) {}
  // The unsigned integer of `size` bytes at the current position; false past the end.
  bool count(int size, bool bigEndian, uint64_t& value, std::string& error) {
    uint8_t b[8] = {};
    for (int i = 0; i < size; ++i) {
      if (!byte(b[i], error)) return false;
    }
    value = 0;
    for (int i = 0; i < size; ++i) value = (value << 8) | b[bigEndian ? i : size - 1 - i];
    return true;
  }
  bool skip(uint64_t n) {
    at_ += n;
    return at_ <= source_.size();
  }
  uint64_t position() const { return at_; }

 private:
  bool byte(uint8_t& b, std::string& error) {
    if (at_ >= source_.size()) return false;
    if (at_ < windowStart_ || at_ >= windowStart_ + window_.size()) {
      windowStart_ = at_;
      if (!source_.read(at_, 1 << 20, buffer_, window_, error)) return false;
    }
    b = uint8_t(window_[at_ - windowStart_]);
    ++at_;
    return true;
  }
  const ByteSource& source_;
  uint64_t at_;
  std::string buffer_;
  std::string_view window_;
  uint64_t windowStart_ = 0;
};

}  // namespace

bool checkPlyComplete(const std::string& path, std::string& error) {
  ByteSource source;
  if (!source.open(path, error)) return false;
  // The header is text up to "end_header" and its line end; 64 kB holds any
  // real one (a few dozen lines).
  std::string buffer;
  std::string_view head;
  if (!source.read(0, 64 << 10, buffer, head, error)) return false;
  size_t end = std::string_view::npos;
  for (size_t at = head.find("end_header"); at != std::string_view::npos; at = head.find("end_header", at + 1)) {
    if (at > 0 && head[at - 1] != '\n') continue;
    const size_t nl = head.find('\n', at);
    if (nl != std::string_view::npos) end = nl + 1;
    break;
  }
  if (end == std::string_view::npos) {
    error = path + ": the PLY header is cut short (no 'end_header' line); the file is damaged or truncated";
    return false;
  }
  std::istringstream lines{std::string(head.substr(0, end))};
  std::string line, format;
  std::vector<Element> elements;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      words >> format;
    } else if (key == "element") {
      Element e;
      words >> e.name >> e.count;
      elements.push_back(e);
    } else if (key == "property" && !elements.empty()) {
      std::string type;
      words >> type;
      Property p;
      if (type == "list") {
        std::string countType, entryType;
        words >> countType >> entryType;
        p.countSize = scalarSize(countType);
        p.size = scalarSize(entryType);
        if (p.countSize == 0 || p.size == 0) return true;  // not ours to judge: Assimp says what it thinks
      } else {
        p.size = scalarSize(type);
        if (p.size == 0) return true;
      }
      elements.back().properties.push_back(p);
    }
  }
  if (format != "binary_little_endian" && format != "binary_big_endian") return true;
  const bool bigEndian = format == "binary_big_endian";

  BodyReader body(source, end);
  auto cutShort = [&](const Element& e, uint64_t row) {
    error = path + ": the PLY file is cut short: it ends at byte " + std::to_string(source.size()) + " in " +
            e.name + " " + std::to_string(row) + " of " + std::to_string(e.count) +
            " its header declares; the file is damaged or truncated";
    return false;
  };
  for (const Element& e : elements) {
    uint64_t fixed = 0;
    bool anyList = false;
    for (const Property& p : e.properties) {
      anyList |= p.countSize != 0;
      fixed += uint64_t(p.size) * (p.countSize == 0);
    }
    if (!anyList) {
      // Fixed-size rows: one comparison for the whole element.
      if (fixed != 0 && e.count > (source.size() - body.position()) / fixed) {
        const uint64_t whole = (source.size() - body.position()) / fixed;
        return cutShort(e, whole + 1);
      }
      body.skip(fixed * e.count);
      continue;
    }
    for (uint64_t row = 0; row < e.count; ++row)
      for (const Property& p : e.properties) {
        uint64_t n = 1;
        if (p.countSize != 0) {
          std::string readError;
          if (!body.count(p.countSize, bigEndian, n, readError)) {
            if (!readError.empty()) return error = readError, false;
            return cutShort(e, row + 1);
          }
        }
        if (!body.skip(n * uint64_t(p.size))) return cutShort(e, row + 1);
      }
  }
  return true;
}

}  // namespace hs::mesh

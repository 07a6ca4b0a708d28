#include "mesh/ply_check.h"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

#include "mesh/declared_counts.h"

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

bool isSigned(const std::string& t) {
  return t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
}

struct Property {
  int size = 0;          // a scalar's size, or a list entry's
  int countSize = 0;     // a list's count type size; 0 for a scalar
  bool signedEntries = false;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  size_t headerLine = 0;
};

// Reads the body sequentially through a 1 MB window: bytes for a binary
// body, white-space separated tokens for an ASCII one.
class BodyReader {
 public:
  BodyReader(const ByteSource& source, uint64_t at) : source_(source), at_(at) {}
  // The integer of `size` bytes at the current position; false past the end.
  bool integer(int size, bool bigEndian, bool isSigned, int64_t& value, std::string& error) {
    uint8_t b[8] = {};
    for (int i = 0; i < size; ++i) {
      if (!byte(b[i], error)) return false;
    }
    uint64_t u = 0;
    for (int i = 0; i < size; ++i) u = (u << 8) | b[bigEndian ? i : size - 1 - i];
    if (isSigned && size < 8 && (u >> (size * 8 - 1)) & 1) u |= ~uint64_t(0) << (size * 8);
    value = int64_t(u);
    return true;
  }
  bool skip(uint64_t n) {
    if (n > source_.size() - std::min(at_, source_.size())) {
      at_ = source_.size() + 1;
      return false;
    }
    at_ += n;
    return true;
  }
  // The next token of an ASCII body (at most 64 characters kept); false at
  // the end of the file.
  bool token(std::string& out, std::string& error) {
    out.clear();
    uint8_t b = 0;
    do {
      if (!byte(b, error)) return false;
    } while (b == ' ' || b == '\t' || b == '\n' || b == '\r');
    do {
      if (out.size() < 64) out += char(b);
      if (!byte(b, error)) return true;
    } while (!(b == ' ' || b == '\t' || b == '\n' || b == '\r'));
    return true;
  }
  uint64_t position() const { return at_; }
  uint64_t left() const { return at_ >= source_.size() ? 0 : source_.size() - at_; }

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

// A PLY count: a whole decimal number that fits 64 bits. `1e9` is not one
// (std::istream read it as 1), nor is -1.
bool parseCount(const std::string& word, uint64_t& value) {
  if (word.empty() || word.find_first_not_of("0123456789") != std::string::npos) return false;
  const auto r = std::from_chars(word.data(), word.data() + word.size(), value);
  return r.ec == std::errc() && r.ptr == word.data() + word.size();
}

// Triangles a face list of n corners makes (a polygon fan).
uint64_t polygonTriangles(int64_t n) { return n >= 3 ? uint64_t(n - 2) : 0; }

// Triangles of one triangle strip list (-1 restarts a strip).
struct StripCounter {
  uint64_t triangles = 0, run = 0;
  void add(int64_t index) {
    if (index < 0) {
      run = 0;
      return;
    }
    if (++run >= 3) ++triangles;
  }
};

}  // namespace

bool checkPly(const ByteSource& source, DeclaredCounts& declared, std::string& error) {
  const std::string& path = source.name();
  declared = {};
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
    error = path + ": the PLY header is cut short (no 'end_header' line" +
            (source.size() > head.size() ? " in its first 64 kB" : "") + "); the file is damaged or truncated";
    return false;
  }
  std::istringstream lines{std::string(head.substr(0, end))};
  std::string line, format;
  std::vector<Element> elements;
  bool judged = true;  // false: a type we do not know; Assimp says what it thinks
  for (size_t lineNo = 1; std::getline(lines, line); ++lineNo) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      words >> format;
    } else if (key == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      e.headerLine = lineNo;
      if (!parseCount(count, e.count)) {
        const bool digits = !count.empty() && count.find_first_not_of("0123456789") == std::string::npos;
        error = path + ":" + std::to_string(lineNo) + ": element " + e.name + ": the count '" + count + "' is " +
                (digits ? "too large" : "not a whole number") + "; the header is damaged";
        return false;
      }
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
        p.signedEntries = isSigned(entryType);
        if (p.countSize == 0 || p.size == 0) judged = false;
      } else {
        p.size = scalarSize(type);
        if (p.size == 0) judged = false;
      }
      elements.back().properties.push_back(p);
    }
  }
  const bool ascii = format == "ascii";
  if (!judged || (!ascii && format != "binary_little_endian" && format != "binary_big_endian")) return true;
  const bool bigEndian = format == "binary_big_endian";

  BodyReader body(source, end);
  auto cutShort = [&](const Element& e, uint64_t row) {
    error = path + ": the PLY file is cut short: it ends at byte " + std::to_string(source.size()) + " in " +
            e.name + " " + std::to_string(row) + " of " + std::to_string(e.count) +
            " its header declares; the file is damaged or truncated";
    return false;
  };
  auto tooMany = [&](const Element& e, uint64_t minBytes) {
    error = path + ":" + std::to_string(e.headerLine) + ": element " + e.name + " declares " +
            std::to_string(e.count) + " rows" +
            (minBytes ? ", which need at least " + std::to_string(minBytes) + " bytes each," : " without properties,") +
            " but only " + std::to_string(body.left()) + " bytes follow byte " +
            std::to_string(body.position()) + "; the file is cut short or its header does not match the data";
    return false;
  };
  uint64_t faceTriangles = 0, stripTriangles = 0;
  bool haveFaces = false, haveStrips = false;
  std::string word;
  for (const Element& e : elements) {
    const bool isFace = e.name == "face", isStrip = e.name == "tristrips";
    haveFaces |= isFace;
    haveStrips |= isStrip;
    uint64_t fixed = 0, minRow = 0;
    bool anyList = false;
    for (const Property& p : e.properties) {
      anyList |= p.countSize != 0;
      fixed += uint64_t(p.size) * (p.countSize == 0);
      // An ASCII value is at least one character and a separator.
      minRow += ascii ? 2 : uint64_t(p.countSize != 0 ? p.countSize : p.size);
    }
    // An element without properties has empty rows: nothing to read (a
    // loop over 10^19 of them would never end). More of them than the file
    // has bytes is a damaged header, which Assimp would try to allocate.
    if (minRow == 0) {
      if (e.count > source.size()) return tooMany(e, 0);
      continue;
    }
    // Refused before a single row is read, so a count of 10^19 costs nothing.
    if (e.count > body.left() / minRow) {
      if (!ascii && !anyList) return cutShort(e, body.left() / minRow + 1);
      return tooMany(e, minRow);
    }
    if (!ascii && !anyList) {
      body.skip(fixed * e.count);
      continue;
    }
    StripCounter strips;
    for (uint64_t row = 0; row < e.count; ++row) {
      bool firstList = true;
      for (const Property& p : e.properties) {
        std::string readError;
        if (ascii) {
          if (!body.token(word, readError)) return readError.empty() ? cutShort(e, row + 1) : (error = readError, false);
          if (p.countSize == 0) continue;
          uint64_t n = 0;
          if (!parseCount(word, n)) {
            error = path + ": " + e.name + " " + std::to_string(row + 1) + " near byte " +
                    std::to_string(body.position()) + ": the list length '" + word + "' is not a whole number";
            return false;
          }
          // Each entry is at least a character and a separator.
          if (n > body.left() / 2 + 1) return cutShort(e, row + 1);
          for (uint64_t i = 0; i < n; ++i) {
            if (!body.token(word, readError))
              return readError.empty() ? cutShort(e, row + 1) : (error = readError, false);
            if (isStrip && firstList) {
              int64_t index = 0;
              std::from_chars(word.data(), word.data() + word.size(), index);
              strips.add(index);
            }
          }
          if (isFace && firstList) faceTriangles += polygonTriangles(int64_t(n));
          if (isStrip && firstList) strips.run = 0;
          firstList = false;
          continue;
        }
        if (p.countSize == 0) {
          if (!body.skip(uint64_t(p.size))) return cutShort(e, row + 1);
          continue;
        }
        int64_t n = 0;
        if (!body.integer(p.countSize, bigEndian, false, n, readError))
          return readError.empty() ? cutShort(e, row + 1) : (error = readError, false);
        if (isStrip && firstList) {
          for (int64_t i = 0; i < n; ++i) {
            int64_t index = 0;
            if (!body.integer(p.size, bigEndian, p.signedEntries, index, readError))
              return readError.empty() ? cutShort(e, row + 1) : (error = readError, false);
            strips.add(index);
          }
          strips.run = 0;
        } else if (!body.skip(uint64_t(n) * uint64_t(p.size))) {
          return cutShort(e, row + 1);
        }
        if (isFace && firstList) faceTriangles += polygonTriangles(n);
        firstList = false;
      }
    }
    stripTriangles += strips.triangles;
  }
  // Data past the last element: the header declares less than the file
  // holds (a count lowered by hand, or two files joined). Read as declared,
  // and said.
  if (body.left() > 0) {
    const uint64_t elementsEnd = body.position();
    bool more = !ascii;
    if (ascii) {
      std::string readError;
      more = body.token(word, readError);
    }
    if (more)
      declared.warnings.push_back(path + ": " + std::to_string(source.size() - end) + " bytes of data follow the header but " +
                                  "its elements end at byte " + std::to_string(elementsEnd) +
                                  "; the rest is not read (the header's counts may be too low)");
  }
  if (haveFaces || haveStrips) {
    declared.triangles = size_t(faceTriangles + stripTriangles);
    declared.by = std::string("PLY ") + (haveFaces ? "face" : "") + (haveFaces && haveStrips ? " and " : "") +
                  (haveStrips ? "tristrips" : "") + " elements";
  }
  return true;
}

bool checkPlyComplete(const std::string& path, std::string& error) {
  ByteSource source;
  if (!source.open(path, error)) return false;
  DeclaredCounts declared;
  return checkPly(source, declared, error);
}

}  // namespace hs::mesh

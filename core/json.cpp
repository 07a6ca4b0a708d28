#include "core/json.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace hs {
namespace {

// "line L, column C" of a byte offset; columns count characters (UTF-8
// continuation bytes are not counted), from 1.
std::string lineColumn(std::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++line;
      column = 1;
    } else if ((c & 0xC0) != 0x80) {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// A walk over the text of a JSON document that reports where values and
// keys start, with their path. Used only to *locate* things (the position
// of a duplicate key, of too deep a nesting, of the value at a path) after
// nlohmann has parsed or refused the text; it stops at anything it does not
// expect, so text that is not JSON past the point of interest is harmless.
class Walker {
 public:
  struct Segment {
    bool isKey;
    std::string key;
    size_t index;
  };
  // Return true to stop the walk.
  std::function<bool(size_t offset, const std::vector<Segment>& path)> onValue;
  std::function<bool(size_t offset, const std::vector<Segment>& objectPath, const std::string& key)> onKey;

  explicit Walker(std::string_view text) : s_(text) {}

  void run() {
    struct Frame {
      bool object;
      size_t count = 0;
    };
    std::vector<Frame> frames;
    std::vector<Segment> path;
    skipSpace();
    // Expecting a value at i_.
    for (;;) {
      if (i_ >= s_.size()) return;
      if (onValue && onValue(i_, path)) return;
      const char c = s_[i_];
      if (c == '{' || c == '[') {
        frames.push_back({c == '{'});
        ++i_;
        skipSpace();
        if (i_ < s_.size() && (s_[i_] == '}' || s_[i_] == ']')) {
          ++i_;
          frames.pop_back();
        } else if (frames.back().object) {
          if (!readKeyInto(path)) return;
          continue;
        } else {
          path.push_back({false, {}, 0});
          continue;
        }
      } else if (c == '"') {
        std::string ignored;
        if (!readString(ignored)) return;
      } else {
        while (i_ < s_.size() && !std::strchr(",]} \t\r\n", s_[i_])) ++i_;
      }
      // After a value: close containers or move to the next element.
      for (;;) {
        skipSpace();
        if (frames.empty() || i_ >= s_.size()) return;
        if (s_[i_] == ',') {
          ++i_;
          skipSpace();
          Frame& f = frames.back();
          ++f.count;
          if (f.object) {
            path.pop_back();
            if (!readKeyInto(path)) return;
          } else {
            path.back().index = f.count;
          }
          break;
        }
        if (s_[i_] == '}' || s_[i_] == ']') {
          ++i_;
          frames.pop_back();
          path.pop_back();
          continue;
        }
        return;
      }
    }
  }

 private:
  // At a key: reads it and the ':' and pushes it onto the path.
  bool readKeyInto(std::vector<Segment>& path) {
    skipSpace();
    const size_t at = i_;
    std::string key;
    if (i_ >= s_.size() || s_[i_] != '"' || !readString(key)) return false;
    if (onKey && onKey(at, path, key)) return false;
    skipSpace();
    if (i_ >= s_.size() || s_[i_] != ':') return false;
    ++i_;
    skipSpace();
    path.push_back({true, std::move(key), 0});
    return true;
  }
  void skipSpace() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r' || s_[i_] == '\n')) ++i_;
  }
  static void appendUtf8(std::string& out, uint32_t cp) {
    if (cp < 0x80) {
      out += char(cp);
    } else if (cp < 0x800) {
      out += char(0xC0 | (cp >> 6));
      out += char(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += char(0xE0 | (cp >> 12));
      out += char(0x80 | ((cp >> 6) & 0x3F));
      out += char(0x80 | (cp & 0x3F));
    } else {
      out += char(0xF0 | (cp >> 18));
      out += char(0x80 | ((cp >> 12) & 0x3F));
      out += char(0x80 | ((cp >> 6) & 0x3F));
      out += char(0x80 | (cp & 0x3F));
    }
  }
  bool hex4(uint32_t& v) {
    if (i_ + 4 > s_.size()) return false;
    v = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[i_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= uint32_t(c - '0');
      else if (c >= 'a' && c <= 'f') v |= uint32_t(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= uint32_t(c - 'A' + 10);
      else return false;
    }
    return true;
  }
  // At '"': the decoded string (so "a" and "\u0061" compare equal).
  bool readString(std::string& out) {
    ++i_;
    while (i_ < s_.size()) {
      const char c = s_[i_++];
      if (c == '"') return true;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= s_.size()) return false;
      const char e = s_[i_++];
      switch (e) {
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          uint32_t cp;
          if (!hex4(cp)) return false;
          if (cp >= 0xD800 && cp <= 0xDBFF && i_ + 6 <= s_.size() && s_[i_] == '\\' && s_[i_ + 1] == 'u') {
            i_ += 2;
            uint32_t lo;
            if (!hex4(lo)) return false;
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          appendUtf8(out, cp);
          break;
        }
        default: out += e;
      }
    }
    return false;
  }

  std::string_view s_;
  size_t i_ = 0;
};

std::string pathString(const std::vector<Walker::Segment>& path) {
  std::string p;
  for (const auto& s : path) p = s.isKey ? jsonPath(p, s.key) : jsonIndex(p, s.index);
  return p;
}

// What the parse callback found that RFC 8259 allows but we refuse.
struct DuplicateKey {
  std::string key;
};
struct TooDeep {};

}  // namespace

std::optional<Json> parseJson(std::string_view text, std::string& error) {
  // Keys seen per open object, innermost last (the callback sees each key
  // once, in order).
  std::vector<std::unordered_set<std::string>> keys;
  Json::parser_callback_t check = [&](int depth, Json::parse_event_t event, Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        if (depth >= kMaxJsonDepth) throw TooDeep{};
        if (event == Json::parse_event_t::object_start) keys.emplace_back();
        break;
      case Json::parse_event_t::object_end:
        keys.pop_back();
        break;
      case Json::parse_event_t::key:
        if (!keys.back().insert(parsed.get<std::string>()).second) throw DuplicateKey{parsed.get<std::string>()};
        break;
      default:
        break;
    }
    return true;
  };
  try {
    return Json::parse(text.begin(), text.end(), check, /*allow_exceptions=*/true, /*ignore_comments=*/false);
  } catch (const DuplicateKey& d) {
    // Find the first key that repeats within its object (an object is
    // identified by its path, which no other object in a document shares).
    size_t where = text.size();
    std::string object;
    std::unordered_map<std::string, std::unordered_set<std::string>> keysOf;
    Walker w(text);
    w.onKey = [&](size_t at, const std::vector<Walker::Segment>& objPath, const std::string& key) {
      const std::string p = pathString(objPath);
      if (!keysOf[p].insert(key).second && key == d.key) {
        where = at;
        object = p;
        return true;
      }
      return false;
    };
    w.run();
    error = lineColumn(text, where) + ": duplicate key \"" + d.key + "\"" + (object.empty() ? "" : " in " + object);
  } catch (const TooDeep&) {
    size_t where = text.size();
    Walker w(text);
    w.onValue = [&](size_t at, const std::vector<Walker::Segment>& path) {
      if (int(path.size()) >= kMaxJsonDepth && (text[at] == '{' || text[at] == '[')) {
        where = at;
        return true;
      }
      return false;
    };
    w.run();
    error = lineColumn(text, where) + ": nested deeper than " + std::to_string(kMaxJsonDepth) + " levels";
  } catch (const Json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 1, column 3: what".
    // The place is recounted from the byte nlohmann stopped at (e.byte
    // counts it, from 1), so it is the offending character's own line and
    // column as everywhere else here: nlohmann puts a raw newline in a
    // string at "line 2, column 0" and counts columns in bytes.
    std::string what = e.what();
    if (const auto at = what.find(" at line "); at != std::string::npos) {
      const auto colon = what.find(": ", at);
      what = colon == std::string::npos ? what.substr(at + 4) : what.substr(colon + 2);
    }
    error = lineColumn(text, e.byte > 0 ? e.byte - 1 : 0) + ": " + what;
  } catch (const Json::out_of_range& e) {
    // A number too large for a double ("1e400"); nlohmann gives no place.
    size_t where = text.size();
    Walker w(text);
    w.onValue = [&](size_t at, const std::vector<Walker::Segment>&) {
      const char c = text[at];
      if (c == '-' || (c >= '0' && c <= '9')) {
        const std::string token(text.substr(at, std::min<size_t>(64, text.size() - at)));
        if (!std::isfinite(std::strtod(token.c_str(), nullptr))) {
          where = at;
          return true;
        }
      }
      return false;
    };
    w.run();
    error = lineColumn(text, where) + ": number out of the range of a double";
  } catch (const std::exception& e) {
    error = e.what();
  }
  return std::nullopt;
}

std::string writeJson(const Json& value, int indent) {
  return value.dump(indent < 0 ? -1 : indent, ' ', false, Json::error_handler_t::replace);
}

std::string jsonLocation(std::string_view text, std::string_view path) {
  size_t where = std::string_view::npos;
  Walker w(text);
  w.onValue = [&](size_t at, const std::vector<Walker::Segment>& p) {
    if (pathString(p) == path) {
      where = at;
      return true;
    }
    return false;
  };
  w.run();
  return where == std::string_view::npos ? std::string() : lineColumn(text, where);
}

std::string jsonErrorIn(std::string_view text, const JsonReader& reader) {
  const std::string& path = reader.errorPath();
  const std::string where = jsonLocation(text, path);
  if (path.empty()) return where.empty() ? reader.errorWhat() : where + ": " + reader.errorWhat();
  return path + (where.empty() ? "" : " (" + where + ")") + ": " + reader.errorWhat();
}

std::string jsonPath(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string jsonIndex(const std::string& parent, size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

const char* jsonTypeName(const Json& v) {
  switch (v.type()) {
    case Json::value_t::object: return "an object";
    case Json::value_t::array: return "an array";
    case Json::value_t::string: return "a string";
    case Json::value_t::boolean: return "true or false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return "a number";
    case Json::value_t::null: return "null";
    default: return "a value of another kind";
  }
}

bool JsonReader::fail(const std::string& path, const std::string& what) {
  if (error_.empty()) {
    error_ = path.empty() ? what : path + ": " + what;
    errorPath_ = path;
    errorWhat_ = what;
  }
  return false;
}

const Json* JsonReader::member(const Json& obj, std::string_view key) {
  if (!obj.is_object()) return nullptr;
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const Json* JsonReader::required(const Json& obj, const std::string& path, std::string_view key) {
  const Json* m = member(obj, key);
  if (!m) fail(jsonPath(path, key), "missing");
  return m;
}

bool JsonReader::object(const Json& v, const std::string& path) {
  return v.is_object() || fail(path, std::string("expected an object, not ") + jsonTypeName(v));
}

bool JsonReader::array(const Json& v, const std::string& path) {
  return v.is_array() || fail(path, std::string("expected an array, not ") + jsonTypeName(v));
}

bool JsonReader::number(const Json& v, const std::string& path, double& out) {
  if (!v.is_number()) return fail(path, std::string("expected a number, not ") + jsonTypeName(v));
  if (!std::isfinite(v.get<double>())) return fail(path, "expected a finite number");
  out = v.get<double>();
  return true;
}

bool JsonReader::number(const Json& v, const std::string& path, double& out, double lo, double hi) {
  double d;
  if (!number(v, path, d)) return false;
  if (d < lo || d > hi)
    return fail(path, "expected a number from " + Json(lo).dump() + " to " + Json(hi).dump() + ", not " + Json(d).dump());
  out = d;
  return true;
}

bool JsonReader::integer(const Json& v, const std::string& path, int64_t& out, int64_t lo, int64_t hi) {
  const std::string range = " from " + std::to_string(lo) + " to " + std::to_string(hi);
  if (v.is_number_integer() && !v.is_number_unsigned()) {
    const int64_t i = v.get<int64_t>();
    if (i < lo || i > hi) return fail(path, "expected a whole number" + range + ", not " + std::to_string(i));
    out = i;
    return true;
  }
  if (v.is_number_unsigned()) {
    const uint64_t u = v.get<uint64_t>();
    if (hi < 0 || u > uint64_t(hi) || (lo > 0 && u < uint64_t(lo)))
      return fail(path, "expected a whole number" + range + ", not " + std::to_string(u));
    out = int64_t(u);
    return true;
  }
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (std::isfinite(d) && d == std::floor(d) && d >= double(lo) && d <= double(hi)) {
      out = int64_t(d);
      return true;
    }
    return fail(path, "expected a whole number" + range + ", not " + v.dump());
  }
  return fail(path, "expected a whole number" + range + ", not " + jsonTypeName(v));
}

bool JsonReader::integer(const Json& v, const std::string& path, int& out, int lo, int hi) {
  int64_t i;
  if (!integer(v, path, i, lo, hi)) return false;
  out = int(i);
  return true;
}

bool JsonReader::boolean(const Json& v, const std::string& path, bool& out) {
  if (!v.is_boolean()) return fail(path, std::string("expected true or false, not ") + jsonTypeName(v));
  out = v.get<bool>();
  return true;
}

bool JsonReader::string(const Json& v, const std::string& path, std::string& out) {
  if (!v.is_string()) return fail(path, std::string("expected a string, not ") + jsonTypeName(v));
  out = v.get<std::string>();
  return true;
}

bool JsonReader::numbers(const Json& v, const std::string& path, double* out, size_t n, const char* shape) {
  const std::string expected = std::string("expected ") + (shape ? shape : std::to_string(n) + " numbers");
  if (!v.is_array()) return fail(path, expected + ", not " + jsonTypeName(v));
  if (v.size() != n) return fail(path, expected + ", not " + std::to_string(v.size()) + " values");
  for (size_t i = 0; i < n; ++i)
    if (!number(v[i], jsonIndex(path, i), out[i])) return false;
  return true;
}

bool JsonReader::optNumber(const Json& obj, const std::string& path, std::string_view key, double& out) {
  const Json* m = member(obj, key);
  return !m || m->is_null() || number(*m, jsonPath(path, key), out);
}

bool JsonReader::optInteger(const Json& obj, const std::string& path, std::string_view key, int& out, int lo, int hi) {
  const Json* m = member(obj, key);
  return !m || m->is_null() || integer(*m, jsonPath(path, key), out, lo, hi);
}

bool JsonReader::optBoolean(const Json& obj, const std::string& path, std::string_view key, bool& out) {
  const Json* m = member(obj, key);
  return !m || m->is_null() || boolean(*m, jsonPath(path, key), out);
}

bool JsonReader::optString(const Json& obj, const std::string& path, std::string_view key, std::string& out) {
  const Json* m = member(obj, key);
  return !m || m->is_null() || string(*m, jsonPath(path, key), out);
}

}  // namespace hs

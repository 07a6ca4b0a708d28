#include "sequencer/json.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace hs::sequencer {

const JsonValue* JsonValue::find(std::string_view key) const {
  if (!isObject()) return nullptr;
  for (const auto& [k, v] : asObject())
    if (k == key) return &v;
  return nullptr;
}

void JsonValue::set(std::string key, JsonValue value) {
  if (!isObject()) v_ = Object{};
  for (auto& [k, v] : asObject())
    if (k == key) {
      v = std::move(value);
      return;
    }
  asObject().emplace_back(std::move(key), std::move(value));
}

namespace {

void writeString(std::string& out, const std::string& s) {
  out += '"';
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(c));
          out += buf;
        } else {
          out += ch;  // UTF-8 passes through
        }
    }
  }
  out += '"';
}

void writeNumber(std::string& out, double d) {
  if (!std::isfinite(d)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, d);  // shortest round-trip form
  out.append(buf, r.ptr);
}

void write(std::string& out, const JsonValue& v, int indent, int depth) {
  auto newline = [&](int d) {
    if (indent < 0) return;
    out += '\n';
    out.append(size_t(indent * d), ' ');
  };
  if (v.isNull()) out += "null";
  else if (v.isBool()) out += v.asBool() ? "true" : "false";
  else if (v.isNumber()) writeNumber(out, v.asNumber());
  else if (v.isString()) writeString(out, v.asString());
  else if (v.isArray()) {
    const auto& a = v.asArray();
    // Arrays of numbers (vectors, quaternions) stay on one line.
    bool flat = true;
    for (const JsonValue& e : a) flat = flat && (e.isNumber() || e.isNull() || e.isBool());
    out += '[';
    for (size_t i = 0; i < a.size(); ++i) {
      if (i) out += (flat && indent >= 0) ? ", " : ",";
      if (!flat) newline(depth + 1);
      write(out, a[i], indent, depth + 1);
    }
    if (!flat && !a.empty()) newline(depth);
    out += ']';
  } else {
    const auto& o = v.asObject();
    out += '{';
    for (size_t i = 0; i < o.size(); ++i) {
      if (i) out += ',';
      newline(depth + 1);
      writeString(out, o[i].first);
      out += indent >= 0 ? ": " : ":";
      write(out, o[i].second, indent, depth + 1);
    }
    if (!o.empty()) newline(depth);
    out += '}';
  }
}

class Reader {
 public:
  Reader(std::string_view text, std::string& error) : s_(text), error_(error) {}

  std::optional<JsonValue> document() {
    auto v = value(0);
    if (!v) return std::nullopt;
    space();
    if (pos_ != s_.size()) return fail("unexpected text after the end of the document");
    return v;
  }

 private:
  std::nullopt_t fail(const std::string& what) {
    size_t line = 1, column = 1;
    for (size_t i = 0; i < pos_ && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    error_ = "line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + what;
    return std::nullopt;
  }
  void space() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\r' || s_[pos_] == '\t')) ++pos_;
  }
  bool literal(std::string_view word) {
    if (s_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  std::optional<JsonValue> value(int depth) {
    if (depth > 256) return fail("nested more than 256 levels deep");
    space();
    if (pos_ >= s_.size()) return fail("unexpected end of text; expected a value");
    const char c = s_[pos_];
    if (c == '{') return object(depth);
    if (c == '[') return array(depth);
    if (c == '"') {
      auto str = string();
      if (!str) return std::nullopt;
      return JsonValue(std::move(*str));
    }
    if (literal("true")) return JsonValue(true);
    if (literal("false")) return JsonValue(false);
    if (literal("null")) return JsonValue();
    return number();
  }

  std::optional<JsonValue> number() {
    const size_t start = pos_;
    // JSON's grammar is stricter than from_chars (no leading '+', no "01",
    // no ".5"): check the shape first.
    size_t p = pos_;
    if (p < s_.size() && s_[p] == '-') ++p;
    if (p >= s_.size() || !std::isdigit(static_cast<unsigned char>(s_[p]))) return fail("expected a value");
    if (s_[p] == '0' && p + 1 < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p + 1])))
      return fail("numbers may not start with 0");
    double d = 0.0;
    const auto r = std::from_chars(s_.data() + start, s_.data() + s_.size(), d);
    if (r.ec == std::errc::result_out_of_range) return fail("number out of range");
    if (r.ec != std::errc()) return fail("expected a number");
    pos_ = size_t(r.ptr - s_.data());
    return JsonValue(d);
  }

  static void appendUtf8(std::string& out, uint32_t cp) {
    if (cp < 0x80) out += char(cp);
    else if (cp < 0x800) {
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

  std::optional<uint32_t> hex4() {
    if (pos_ + 4 > s_.size()) return std::nullopt;
    uint32_t v = 0;
    const auto r = std::from_chars(s_.data() + pos_, s_.data() + pos_ + 4, v, 16);
    if (r.ec != std::errc() || r.ptr != s_.data() + pos_ + 4) return std::nullopt;
    pos_ += 4;
    return v;
  }

  std::optional<std::string> string() {
    ++pos_;  // opening quote
    std::string out;
    while (true) {
      if (pos_ >= s_.size()) return fail("unterminated string");
      const char c = s_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) return fail("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= s_.size()) return fail("unterminated string");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          auto cp = hex4();
          if (!cp) return fail("bad \\u escape");
          if (*cp >= 0xD800 && *cp < 0xDC00 && literal("\\u")) {
            auto lo = hex4();
            if (!lo || *lo < 0xDC00 || *lo >= 0xE000) return fail("bad surrogate pair");
            *cp = 0x10000 + ((*cp - 0xD800) << 10) + (*lo - 0xDC00);
          }
          appendUtf8(out, *cp);
          break;
        }
        default: --pos_; return fail("unknown escape in a string");
      }
    }
  }

  std::optional<JsonValue> array(int depth) {
    ++pos_;
    JsonValue::Array a;
    space();
    if (pos_ < s_.size() && s_[pos_] == ']') {
      ++pos_;
      return JsonValue(std::move(a));
    }
    while (true) {
      auto v = value(depth + 1);
      if (!v) return std::nullopt;
      a.push_back(std::move(*v));
      space();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == ']') {
        ++pos_;
        return JsonValue(std::move(a));
      }
      return fail("expected ',' or ']'");
    }
  }

  std::optional<JsonValue> object(int depth) {
    ++pos_;
    JsonValue::Object o;
    space();
    if (pos_ < s_.size() && s_[pos_] == '}') {
      ++pos_;
      return JsonValue(std::move(o));
    }
    while (true) {
      space();
      if (pos_ >= s_.size() || s_[pos_] != '"') return fail("expected a member name in quotes");
      auto key = string();
      if (!key) return std::nullopt;
      space();
      if (pos_ >= s_.size() || s_[pos_] != ':') return fail("expected ':' after the member name");
      ++pos_;
      auto v = value(depth + 1);
      if (!v) return std::nullopt;
      o.emplace_back(std::move(*key), std::move(*v));
      space();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == '}') {
        ++pos_;
        return JsonValue(std::move(o));
      }
      return fail("expected ',' or '}'");
    }
  }

  std::string_view s_;
  std::string& error_;
  size_t pos_ = 0;
};

}  // namespace

std::string writeJson(const JsonValue& value, int indent) {
  std::string out;
  write(out, value, indent, 0);
  return out;
}

std::optional<JsonValue> readJson(std::string_view text, std::string& error) {
  return Reader(text, error).document();
}

}  // namespace hs::sequencer

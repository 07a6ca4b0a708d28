#pragma once
// Messages quote file content ("line 3: 'v 1 2 \r'"); a raw carriage return,
// escape sequence or NUL in one would overwrite or garble the terminal line
// (an OBJ error printed as "v ')"). Every line shown to the user goes through
// this: control bytes become visible C escapes, everything else (UTF-8
// included) stays as it is.
#include <string>
#include <string_view>

namespace hs {

inline std::string escapeControlCharacters(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7f) {
      out += ch;
      continue;
    }
    switch (c) {
      case '\r': out += "\\r"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        out += "\\x";
        out += kHex[c >> 4];
        out += kHex[c & 15];
    }
  }
  return out;
}

}  // namespace hs

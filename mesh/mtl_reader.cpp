#include "mesh/mtl_reader.h"

#include <charconv>
#include <sstream>

#include "mesh/byte_source.h"

namespace hs::mesh {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// map_Kd may carry options (-s 1 1 1, -o ..., -bm 1, -clamp on) before the
// file name; the name itself may contain spaces. Skip known options with
// their argument counts and take the rest of the line as the name.
std::string mapFileName(const std::string& rest) {
  std::istringstream in(rest);
  std::vector<std::string> tokens;
  for (std::string t; in >> t;) tokens.push_back(t);
  size_t i = 0;
  auto argCount = [](const std::string& opt) -> int {
    if (opt == "-s" || opt == "-o" || opt == "-t") return 3;
    if (opt == "-mm") return 2;
    if (opt == "-bm" || opt == "-boost" || opt == "-clamp" || opt == "-blendu" ||
        opt == "-blendv" || opt == "-texres" || opt == "-imfchan" || opt == "-cc")
      return 1;
    return -1;
  };
  while (i < tokens.size() && tokens[i].size() > 1 && tokens[i][0] == '-') {
    const int n = argCount(tokens[i]);
    if (n < 0) break;
    ++i;
    // -s/-o/-t take 1 to 3 numbers.
    for (int k = 0; k < n && i < tokens.size(); ++k) {
      double v;
      const auto& tk = tokens[i];
      if (n == 3 && k > 0 && std::from_chars(tk.data(), tk.data() + tk.size(), v).ec != std::errc())
        break;
      ++i;
    }
  }
  std::string name;
  for (; i < tokens.size(); ++i) name += (name.empty() ? "" : " ") + tokens[i];
  return name;
}

}  // namespace

bool readMtl(const std::string& path, std::vector<MtlMaterial>& out, std::string& error,
             std::vector<std::string>* warnings) {
  std::string text, readError;
  if (!readWholeFile(path, text, readError)) {
    error = "material library " + readError;  // "material library a.mtl: file not found"
    return false;
  }
  std::istringstream in(text);
  std::string line;
  int lineNo = 0;
  MtlMaterial* cur = nullptr;
  while (std::getline(in, line)) {
    ++lineNo;
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    const auto sp = line.find_first_of(" \t");
    const std::string key = line.substr(0, sp);
    const std::string rest = sp == std::string::npos ? "" : trim(line.substr(sp));
    if (key == "newmtl") {
      out.push_back({});
      cur = &out.back();
      cur->name = rest;
    } else if (!cur) {
      continue;
    } else if (key == "Kd") {
      std::istringstream v(rest);
      glm::vec3 c;
      if (v >> c.r >> c.g >> c.b)
        cur->kd = c;
      else {
        error = path + ":" + std::to_string(lineNo) + ": cannot read Kd colour '" + rest + "'";
        return false;
      }
    } else if (key == "d") {
      std::istringstream v(rest);
      float d;
      if (v >> d) cur->opacity = d;
    } else if (key == "Tr") {
      std::istringstream v(rest);
      float t;
      if (v >> t) cur->opacity = 1.0f - t;
    } else if (key == "map_Kd") {
      cur->diffuseMap = mapFileName(rest);
    }
  }
  // Cut short mid-line, `Kd 0.8 0.6 0.25` still reads as `Kd 0.8 0.6 0.`:
  // a missing final line end is said, never silent.
  const size_t lastLineStart = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  const std::string lastLine = trim(text.substr(lastLineStart));
  if (warnings && !lastLine.empty())
    warnings->push_back(path + ":" + std::to_string(lineNo) +
                        ": the file does not end with a line end, so it may have been cut short; its last line ('" +
                        lastLine.substr(0, 60) + "') was read as it stands");
  return true;
}

}  // namespace hs::mesh

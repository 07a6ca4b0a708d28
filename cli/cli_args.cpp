#include "cli/cli_args.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace hs::cli {

bool parseArgs(int argc, char** argv, int first, const std::vector<OptionSpec>& specs, Args& out,
               std::string& error) {
  for (int i = first; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      out.help = true;
      continue;
    }
    if (a.size() > 2 && a.rfind("--", 0) == 0) {
      std::string name = a.substr(2), value;
      bool inlineValue = false;
      if (const auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        inlineValue = true;
      }
      const OptionSpec* spec = nullptr;
      for (const auto& s : specs)
        if (s.name == name) spec = &s;
      if (!spec) {
        error = "unknown option --" + name;
        return false;
      }
      if (spec->takesValue && !inlineValue) {
        if (i + 1 >= argc) {
          error = "option --" + name + " needs a value";
          return false;
        }
        value = argv[++i];
      } else if (!spec->takesValue) {
        if (inlineValue) {
          error = "option --" + name + " takes no value";
          return false;
        }
        value = "1";
      }
      out.options[name] = value;
      continue;
    }
    out.positional.push_back(a);
  }
  return true;
}

bool parseSize(const std::string& text, int& width, int& height, std::string& error) {
  const auto x = text.find('x');
  auto parseInt = [](const std::string& s, int& v) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
  };
  if (x == std::string::npos || !parseInt(text.substr(0, x), width) || !parseInt(text.substr(x + 1), height)) {
    error = "size '" + text + "' is not WIDTHxHEIGHT (for example 1920x1080)";
    return false;
  }
  if (width < 1 || height < 1 || width > 16384 || height > 16384) {
    error = "size " + text + " is out of range (1 to 16384 pixels per side)";
    return false;
  }
  return true;
}

bool parseVec3(const std::string& text, double out[3], std::string& error) {
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = text.find(',', start);
    const bool last = i == 2;
    if ((!last && comma == std::string::npos) || (last && comma != std::string::npos)) {
      error = "'" + text + "' is not three numbers x,y,z";
      return false;
    }
    std::string part = text.substr(start, last ? std::string::npos : comma - start);
    if (!part.empty() && part[0] == '+') part.erase(0, 1);
    const auto r = std::from_chars(part.data(), part.data() + part.size(), out[i]);
    if (r.ec != std::errc() || r.ptr != part.data() + part.size() || !std::isfinite(out[i])) {
      error = "'" + text + "' is not three finite numbers x,y,z";
      return false;
    }
    start = comma + 1;
  }
  return true;
}

int fail(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "hybridscape-cli %s: error: %s\n", command.c_str(), message.c_str());
  return 1;
}

int usage(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "hybridscape-cli %s: %s (see hybridscape-cli %s --help)\n", command.c_str(), message.c_str(),
               command.c_str());
  return 2;
}

}  // namespace hs::cli

#pragma once
// Argument parsing for hybridscape-cli subcommands: positionals and
// --name value / --name=value options, with one-line errors.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace hs::cli {

struct OptionSpec {
  std::string name;   // without dashes
  bool takesValue = true;
};

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::string> options;  // flags map to "1"
  bool help = false;

  bool has(const std::string& name) const { return options.count(name) > 0; }
  std::optional<std::string> get(const std::string& name) const {
    auto it = options.find(name);
    return it == options.end() ? std::nullopt : std::optional(it->second);
  }
};

// Parses argv[first..]. False with `error` on an unknown option or a missing value.
bool parseArgs(int argc, char** argv, int first, const std::vector<OptionSpec>& specs, Args& out,
               std::string& error);

// "1920x1080" -> (1920, 1080); sizes from 1 to 16384.
bool parseSize(const std::string& text, int& width, int& height, std::string& error);
// "x,y,z" -> three finite doubles.
bool parseVec3(const std::string& text, double out[3], std::string& error);

// Failure of a subcommand: prints "hybridscape-cli <cmd>: error: <msg>" and returns 1.
int fail(const std::string& command, const std::string& message);
// Usage error (exit code 2).
int usage(const std::string& command, const std::string& message);

}  // namespace hs::cli

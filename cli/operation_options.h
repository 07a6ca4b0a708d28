#pragma once
// A subcommand's command line, parsed with CLI11 from its operation's
// declaration (core/params.h): every declared parameter with a CLI option
// becomes an option (a flag, or an option taking one value) whose help is
// the declaration's, and every value given is checked by the declaration
// (range, unit, whole numbers, choices) before the command runs, so a bad
// value is one line naming the option, the value and the range, exit 2.
//
// Behaviour kept from the hand parser it replaced: --name value and
// --name=value; a value may start with '-' ("--budget -1,2"); given twice,
// the last wins; positionals may come anywhere; -h/--help prints the help
// on stdout (exit 0); errors are "hybridscape-cli <cmd>: <what> (see
// hybridscape-cli <cmd> --help)" with exit 2.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/params.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace hs::cli {

class OperationArgs {
 public:
  explicit OperationArgs(const OperationDecl& op);
  ~OperationArgs();
  OperationArgs(const OperationArgs&) = delete;
  OperationArgs& operator=(const OperationArgs&) = delete;

  // Parses argv (the arguments after the command's name) and checks every
  // value given. Returns the exit code to end with now (0 after printing
  // the help, 2 after a usage error), or nullopt to go on.
  std::optional<int> parse(int argc, char** argv);

  const OperationDecl& operation() const { return op_; }
  const std::vector<std::string>& positionals() const { return positionals_; }

  // Whether the option of parameter `key` was given.
  bool has(std::string_view key) const;
  // How many declared options were given.
  size_t givenCount() const { return values_.size(); }
  // The checked value of `key`: what was given, else the default, else null.
  const Json& value(std::string_view key) const;
  // Typed views of value(): text (a choice's or a text's; "" if null),
  // number, whole number, flag (false if not given), numbers of a tuple.
  std::string text(std::string_view key) const;
  std::optional<std::string> given(std::string_view key) const;  // the text, if given
  double number(std::string_view key) const;
  int64_t integer(std::string_view key) const;
  bool flag(std::string_view key) const;
  std::vector<double> numbers(std::string_view key) const;

  // "hybridscape-cli <cmd>: error: <message>" on stderr; returns 1.
  int fail(const std::string& message) const;
  // "hybridscape-cli <cmd>: <message> (see hybridscape-cli <cmd> --help)"; returns 2.
  int usage(const std::string& message) const;

  // The --help text (also for tests and the documentation).
  std::string help() const;

 private:
  const OperationDecl& op_;
  std::unique_ptr<CLI::App> app_;
  std::map<std::string, std::string, std::less<>> raw_;  // by key, the option's text as given
  std::map<std::string, bool, std::less<>> flags_;       // by key
  std::map<std::string, CLI::Option*, std::less<>> options_;
  std::map<std::string, Json, std::less<>> values_;  // by key, what was given, checked
  std::vector<std::string> positionals_;
};

// Failure and usage lines of a command that has no OperationArgs (the
// dispatchers of `terrain` and `farm`).
int failCommand(const std::string& command, const std::string& message);
int usageCommand(const std::string& command, const std::string& message);

}  // namespace hs::cli

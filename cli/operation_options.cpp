#include "cli/operation_options.h"

#include <algorithm>
#include <cstdio>

#include <CLI/CLI.hpp>

#include "core/escape_control.h"

namespace hs::cli {
namespace {

constexpr size_t kColumn = 30;   // where an option's help starts
constexpr size_t kWidth = 100;   // the help's line width

// Words of `text` in lines of at most `width` characters; explicit line
// breaks are kept.
std::string wrap(const std::string& text, size_t width, size_t indent = 0) {
  std::string out, line;
  auto flush = [&] {
    out += line;
    line.clear();
  };
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string para = text.substr(start, end - start);
    // Lines that start with spaces are preformatted (tables, examples).
    if (!para.empty() && para[0] == ' ') {
      line = para;
    } else {
      size_t pos = 0;
      while (pos < para.size()) {
        size_t next = para.find(' ', pos);
        if (next == std::string::npos) next = para.size();
        const std::string word = para.substr(pos, next - pos);
        if (!line.empty() && line.size() + 1 + word.size() > width) {
          flush();
          out += "\n" + std::string(indent, ' ');
        }
        line += (line.empty() ? "" : " ") + word;
        pos = next + 1;
      }
    }
    flush();
    if (end == text.size()) break;
    out += "\n" + (end + 1 < text.size() && text[end + 1] != '\n' ? std::string(indent, ' ') : std::string());
    start = end + 1;
  }
  return out;
}

// CLI11's help with the declaration's usage line first (the form the CLI
// always had: "usage: hybridscape-cli <cmd> ..."), then the description,
// the positionals, CLI11's option groups, and the notes.
class HelpFormatter : public CLI::Formatter {
 public:
  explicit HelpFormatter(const OperationDecl& op) : op_(op) { column_width(kColumn); }

  std::string make_help(const CLI::App* app, std::string, CLI::AppFormatMode mode) const override {
    std::string out = "usage: hybridscape-cli " + op_.name + (op_.usage.empty() ? "" : " " + op_.usage) + "\n";
    if (!op_.description.empty()) out += "\n" + wrap(op_.description, kWidth) + "\n";
    if (!op_.positionals.empty()) {
      out += "\nArguments:\n";
      for (const PositionalDecl& p : op_.positionals) {
        std::string name = "  <" + p.name + ">" + (p.repeated ? " ..." : "");
        name.resize(std::max(name.size() + 1, kColumn), ' ');
        out += name + wrap(p.help, kWidth - kColumn, kColumn) + "\n";
      }
    }
    out += make_groups(app, mode);
    if (!op_.notes.empty()) out += "\n" + wrap(op_.notes, kWidth) + "\n";
    // CLI11 puts an empty line before and after each group: one is enough.
    for (size_t at; (at = out.find("\n\n\n")) != std::string::npos;) out.erase(at, 1);
    return out;
  }

  std::string make_option_desc(const CLI::Option* opt) const override {
    // CLI11 indents the lines after the first to the column itself.
    return wrap(opt->get_description(), kWidth - kColumn);
  }

 private:
  const OperationDecl& op_;
};

// One line, whatever file content the message quotes (core/escape_control.h).
void printLine(const std::string& line) { std::fprintf(stderr, "%s\n", escapeControlCharacters(line).c_str()); }

}  // namespace

OperationArgs::OperationArgs(const OperationDecl& op) : op_(op), app_(std::make_unique<CLI::App>(op.summary, op.name)) {
  CLI::App& app = *app_;
  app.formatter(std::make_shared<HelpFormatter>(op));
  app.set_help_flag("-h,--help", "print this help");
  app.allow_extras(true);  // unknown options are reported below, one line
  app.add_option("arguments", positionals_)->group("");
  for (const ParamDecl& p : op.params) {
    if (p.option.empty()) continue;
    const std::string group = p.group.empty() ? std::string("Options") : "Options, " + p.group;
    CLI::Option* o = nullptr;
    if (p.type == ParamType::Flag) {
      o = app.add_flag("--" + p.option, flags_[p.key], paramHelp(p));
    } else {
      o = app.add_option("--" + p.option, raw_[p.key], paramHelp(p));
      const std::string valueName = p.valueName.empty() ? std::string("VALUE") : p.valueName;
      o->option_text(valueName);
      o->type_name(valueName);  // "--out: 1 required FILE missing"
    }
    o->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    o->group(group);
    options_[p.key] = o;
  }
}

OperationArgs::~OperationArgs() = default;

std::optional<int> OperationArgs::parse(int argc, char** argv) {
  std::vector<std::string> args(argv, argv + argc);
  // CLI11 splits a value written "[a,b]" into a list of its own; a JSON list
  // (`set Snow particles.rate_keys "[[0, 100], [30, 400]]"`) must arrive
  // as typed. A marker in front hides the bracket; it is taken off below.
  constexpr char kKeep = '\x1f';
  for (std::string& a : args)
    if (!a.empty() && a.front() == '[') a.insert(a.begin(), kKeep);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  const auto unmark = [&] {
    auto strip = [](std::string& v) {
      if (!v.empty() && v.front() == kKeep) v.erase(v.begin());
    };
    for (std::string& v : positionals_) strip(v);
    for (auto& [key, v] : raw_) strip(v);
  };
  try {
    app_->parse(args);
    unmark();
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", help().c_str());
    return 0;
  } catch (const CLI::ParseError& e) {
    return usage(e.what());
  }
  for (std::string extra : app_->remaining()) {
    if (!extra.empty() && extra.front() == kKeep) extra.erase(extra.begin());
    return usage(extra.rfind("-", 0) == 0 ? "unknown option " + extra : "unexpected argument '" + extra + "'");
  }
  for (const ParamDecl& p : op_.params) {
    if (p.option.empty()) continue;
    const CLI::Option* o = options_.at(p.key);
    if (o->count() == 0) {
      if (p.required) return usage("--" + p.option + (p.valueName.empty() ? "" : " " + p.valueName) + " is required");
      continue;
    }
    if (p.type == ParamType::Flag) {
      values_[p.key] = flags_.at(p.key);
      continue;
    }
    std::string error;
    const std::optional<Json> v = parseParam(p, raw_.at(p.key), error);
    if (!v) return usage(error);
    values_[p.key] = *v;
  }
  return std::nullopt;
}

bool OperationArgs::has(std::string_view key) const { return values_.find(key) != values_.end(); }

const Json& OperationArgs::value(std::string_view key) const {
  if (auto it = values_.find(key); it != values_.end()) return it->second;
  return op_.param(key).defaultValue;
}

std::string OperationArgs::text(std::string_view key) const {
  const Json& v = value(key);
  return v.is_string() ? v.get<std::string>() : std::string();
}

std::optional<std::string> OperationArgs::given(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  if (auto it = raw_.find(key); it != raw_.end()) return it->second;
  return std::nullopt;
}

double OperationArgs::number(std::string_view key) const {
  const Json& v = value(key);
  return v.is_number() ? v.get<double>() : 0.0;
}

int64_t OperationArgs::integer(std::string_view key) const {
  const Json& v = value(key);
  return v.is_number() ? v.get<int64_t>() : 0;
}

bool OperationArgs::flag(std::string_view key) const {
  const Json& v = value(key);
  return v.is_boolean() && v.get<bool>();
}

std::vector<double> OperationArgs::numbers(std::string_view key) const {
  std::vector<double> out;
  for (const Json& v : value(key))
    if (v.is_number()) out.push_back(v.get<double>());
  return out;
}

int OperationArgs::fail(const std::string& message) const { return failCommand(op_.name, message); }

int OperationArgs::usage(const std::string& message) const { return usageCommand(op_.name, message); }

std::string OperationArgs::help() const { return app_->help(); }

int failCommand(const std::string& command, const std::string& message) {
  printLine("hybridscape-cli " + command + ": error: " + message);
  return 1;
}

int usageCommand(const std::string& command, const std::string& message) {
  printLine("hybridscape-cli " + command + ": " + message + " (see hybridscape-cli " + command + " --help)");
  return 2;
}

}  // namespace hs::cli

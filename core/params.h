#pragma once
// Parameters of operations, declared once (DESIGN.md, "Edits"): what an
// operation the editor and the command line share takes, with its type,
// unit, range, default and help. From one declaration come the CLI's
// options and --help (cli/operation_options.h), the editor's widgets
// (app/param_widgets.h), the clamping the domain code does on values from
// files and calls, the JSON keys of reports, and the tests' range checks,
// so the frontends can differ in presentation but never in ranges or rules
// (as scene/fields.cpp is for properties).
//
// Values are hs::Json: a number (integers as integers), a bool (a flag), a
// string (a choice's name, a text), or an array of numbers (a tuple such as
// a size 1920x1080 or a position x,y,z).
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/json.h"

namespace hs {

enum class ParamType {
  Number,  // `count` numbers (1: a scalar), each in [min, max]; whole numbers when `integer`
  Flag,    // on or off (CLI: --name alone)
  Choice,  // one of `choices`
  Text,    // free text (a name, a file, a frame list): the operation reads and checks it
};

// Units say what a number measures: words in messages and help ("0 to 90
// degrees"), a symbol in the editor's fields ("35°").
enum class Unit { None, Metres, Degrees, Pixels, Samples, Seconds, Percent, PerSecond, MetresPerSecond, Levels };
const char* unitWords(Unit u);   // "metres", "degrees"; "" for None
const char* unitSymbol(Unit u);  // "m", "°"; "" for None

struct ParamDecl {
  std::string key{};     // JSON key in reports, the editor widget's name: "talus_deg"
  std::string option{};  // CLI option without dashes ("talus"); empty: no CLI option
  std::string label{};   // the editor's label: "Talus angle"
  ParamType type = ParamType::Number;
  Unit unit = Unit::None;
  double min = 0.0, max = 0.0;  // inclusive, for every number of a tuple
  bool integer = false;
  Json defaultValue{};  // null: no default (an optional or a required value)
  // Choice: the names, in the order the editor lists them; "h265|hevc"
  // is the name h265 also accepted as hevc.
  std::vector<std::string> choices{};
  std::string help{};     // one sentence, for --help and tooltips
  std::string valueName{};  // what --help shows after the option: "DEG", "WxH"
  int count = 1;          // Number: how many numbers
  char separator = ',';   // Number with count > 1: between them ("1920x1080": 'x')
  bool oneForAll = false;  // Number with count > 1: a single number stands for all ("2000" = 2000x2000)
  bool required = false;   // the CLI refuses to run without it
  bool editor = false;     // the editor shows a widget for it (tests check the widget's range)
  int decimals = 3;        // the editor's number field
  double step = 1.0;       // the editor's spin step
  std::string group{};     // --help section ("thermal"); empty: the options
  // Number with count > 1: ranges of their own per number, when they
  // differ ({{-100, 0}, {0, 100}}: NEAR <= 0 <= FAR); empty: [min, max] each.
  std::vector<std::pair<double, double>> componentRanges{};
  bool ordered = false;  // Number with count > 1: no number below the one before it (MIN,MAX; FIRST-LAST)
};

// The range of number `i` of a tuple (componentRanges, else [min, max]).
double componentMin(const ParamDecl& p, int i);
double componentMax(const ParamDecl& p, int i);

// "--talus" for a CLI option, else the label.
std::string paramName(const ParamDecl& p);
// "0 to 90 degrees" (and "each" for tuples); "" for non-numbers.
std::string rangeText(const ParamDecl& p);
// The help line: the help with range, choices and default
// ("angle of repose (0 to 90 degrees; default 35)").
std::string paramHelp(const ParamDecl& p);

// Shortest text that reads back to the same double ("0.1", "1000000", "1e-06").
std::string formatNumber(double v);
// A value as a user types it: "35", "1920x1080", "sbs", "true".
std::string formatParamValue(const ParamDecl& p, const Json& value);

// Text a user typed (a CLI option's value, a dialog's field) as a checked
// value. nullopt with `error` naming the option, the text and the range:
// "--talus: 95 is out of range (0 to 90 degrees)", "--talus takes a number
// (0 to 90 degrees), not 'steep'". A flag reads "1", "true", "on", "0",
// "false", "off".
std::optional<Json> parseParam(const ParamDecl& p, std::string_view text, std::string& error);
// Checks a value that did not come as text (a widget, a file, a struct)
// with the same rules and messages.
bool checkParam(const ParamDecl& p, const Json& value, std::string& error);

// For places that must accept and repair (values from files, domain calls):
// `v` clamped into [min, max] (rounded for whole numbers), NaN replaced by
// the default, and a warning naming it when it changed ("thermal erosion:
// Talus angle 95 is out of range (0 to 90 degrees); using 90"). `context`
// prefixes the warning.
double clampParam(const ParamDecl& p, double v, std::vector<std::string>& warnings, std::string_view context = {});

// The default as a number (0 when it has none): for structs' initialisers
// and widgets.
double defaultNumber(const ParamDecl& p);

// A positional argument of an operation ("<scene.hscene>").
struct PositionalDecl {
  std::string name{};  // "scene.hscene"
  std::string help{};
  bool repeated = false;  // one or more ("<mesh-file> [more tiles ...]")
};

struct OperationDecl {
  std::string name{};       // "terrain erode": the CLI command line, the editor's action
  std::string summary{};    // one line, for command lists
  std::string usage{};      // after the name in the usage line: "<scene.hscene> --thermal|--hydraulic [options]"
  std::string description{};  // what it does, for --help
  std::string notes{};      // after the options in --help: examples, caveats
  std::vector<PositionalDecl> positionals{};
  std::vector<ParamDecl> params{};

  // The parameter with this key; nullptr if none.
  const ParamDecl* find(std::string_view key) const;
  // The parameter with this key; throws std::logic_error if there is none
  // (a key that is not declared is a programming error).
  const ParamDecl& param(std::string_view key) const;
};

// The values an operation used as a JSON object keyed by its declaration,
// in declaration order: every declared key that `values` holds, else its
// default. Keys `values` holds that are not declared are left out. For
// reports ("the JSON keys of its report").
Json paramsJson(const OperationDecl& op, const Json& values);

// Appends `more` to `to` (operations made of several structs' parameters).
void appendParams(std::vector<ParamDecl>& to, const std::vector<ParamDecl>& more);
// The parameter with this key in `params`; throws std::logic_error if there
// is none (as OperationDecl::param).
const ParamDecl& paramIn(const std::vector<ParamDecl>& params, std::string_view key);

}  // namespace hs

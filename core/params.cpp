#include "core/params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace hs {
namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The names a choice entry accepts: "h265|hevc" -> h265, hevc.
std::vector<std::string_view> choiceNames(std::string_view entry) {
  std::vector<std::string_view> out;
  size_t start = 0;
  while (true) {
    const size_t bar = entry.find('|', start);
    out.push_back(entry.substr(start, bar == std::string_view::npos ? std::string_view::npos : bar - start));
    if (bar == std::string_view::npos) return out;
    start = bar + 1;
  }
}

std::string canonicalChoice(std::string_view entry) { return std::string(choiceNames(entry).front()); }

std::string choiceList(const ParamDecl& p) {
  std::string out;
  for (const std::string& c : p.choices) out += (out.empty() ? "" : ", ") + canonicalChoice(c);
  return out;
}

enum class NumberRead { Ok, NotANumber, NotWhole, TooLarge };

// One number as typed: an optional '+', then what from_chars reads, and
// nothing after it. Whole numbers must be written as such ("2.5" and "1e3"
// are not whole numbers); numbers must be finite.
NumberRead readNumber(std::string_view text, bool integer, double& out) {
  std::string_view s = trimmed(text);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return NumberRead::NotANumber;
  if (integer) {
    long long v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec == std::errc() && r.ptr == s.data() + s.size()) {
      out = double(v);
      return NumberRead::Ok;
    }
    if (r.ec == std::errc::result_out_of_range && r.ptr == s.data() + s.size()) return NumberRead::TooLarge;
    double d = 0.0;
    const auto rd = std::from_chars(s.data(), s.data() + s.size(), d);
    return rd.ec == std::errc() && rd.ptr == s.data() + s.size() && std::isfinite(d) ? NumberRead::NotWhole
                                                                                   : NumberRead::NotANumber;
  }
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  if (r.ptr != s.data() + s.size()) return NumberRead::NotANumber;
  if (r.ec == std::errc::result_out_of_range) return NumberRead::TooLarge;
  if (r.ec != std::errc() || !std::isfinite(out)) return NumberRead::NotANumber;
  return NumberRead::Ok;
}

bool inRange(const ParamDecl& p, int i, double v) { return v >= componentMin(p, i) && v <= componentMax(p, i); }

std::string parenRange(const ParamDecl& p) { return " (" + rangeText(p) + ")"; }

// What an ordered tuple's refusal says: "'9,1' is not in order (MIN <= MAX)".
std::string orderText(const ParamDecl& p) {
  std::string names = p.valueName;
  for (char& c : names)
    if (c == p.separator) c = ' ';
  std::string out;
  size_t start = 0;
  while (start < names.size()) {
    size_t end = names.find(' ', start);
    if (end == std::string::npos) end = names.size();
    out += (out.empty() ? "" : " <= ") + names.substr(start, end - start);
    start = end + 1;
  }
  return out.empty() ? std::string("each number at least the one before") : out;
}

}  // namespace

const char* unitWords(Unit u) {
  switch (u) {
    case Unit::None: return "";
    case Unit::Metres: return "metres";
    case Unit::Degrees: return "degrees";
    case Unit::Pixels: return "pixels";
    case Unit::Samples: return "samples";
    case Unit::Seconds: return "seconds";
    case Unit::Percent: return "percent";
    case Unit::PerSecond: return "per second";
    case Unit::MetresPerSecond: return "metres per second";
    case Unit::Levels: return "levels";
  }
  return "";
}

const char* unitSymbol(Unit u) {
  switch (u) {
    case Unit::None: return "";
    case Unit::Metres: return "m";
    case Unit::Degrees: return "°";
    case Unit::Pixels: return "px";
    case Unit::Samples: return "samples";
    case Unit::Seconds: return "s";
    case Unit::Percent: return "%";
    case Unit::PerSecond: return "/s";
    case Unit::MetresPerSecond: return "m/s";
    case Unit::Levels: return "levels";
  }
  return "";
}

double componentMin(const ParamDecl& p, int i) {
  return i >= 0 && size_t(i) < p.componentRanges.size() ? p.componentRanges[size_t(i)].first : p.min;
}

double componentMax(const ParamDecl& p, int i) {
  return i >= 0 && size_t(i) < p.componentRanges.size() ? p.componentRanges[size_t(i)].second : p.max;
}

std::string paramName(const ParamDecl& p) { return p.option.empty() ? p.label : "--" + p.option; }

std::string rangeText(const ParamDecl& p) {
  if (p.type != ParamType::Number) return {};
  std::string s;
  if (p.componentRanges.empty()) {
    s = formatNumber(p.min) + " to " + formatNumber(p.max);
  } else {
    for (const auto& [lo, hi] : p.componentRanges) s += (s.empty() ? "" : ", ") + formatNumber(lo) + " to " + formatNumber(hi);
  }
  if (p.unit != Unit::None) s += std::string(" ") + unitWords(p.unit);
  if (p.count > 1 && p.componentRanges.empty()) s += " each";
  if (p.ordered) s += ", " + orderText(p);
  return s;
}

std::string paramHelp(const ParamDecl& p) {
  std::string extra;
  if (p.type == ParamType::Number) extra = rangeText(p);
  else if (p.type == ParamType::Choice) extra = choiceList(p);
  if (!p.defaultValue.is_null() && p.type != ParamType::Flag)
    extra += (extra.empty() ? "default " : "; default ") + formatParamValue(p, p.defaultValue);
  if (extra.empty()) return p.help;
  return p.help.empty() ? extra : p.help + " (" + extra + ")";
}

std::string formatNumber(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
  // Shortest exact digits; plain decimals where people write them so
  // ("0.0001", not "1e-04"), exponents for the very small and very large.
  const bool plain = std::abs(v) >= 1e-5 && std::abs(v) < 1e15;
  char buf[400];
  const auto r = plain ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                       : std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string formatParamValue(const ParamDecl& p, const Json& value) {
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number()) return formatNumber(value.get<double>());
  if (value.is_array()) {
    std::string out;
    for (const Json& v : value) {
      if (!out.empty()) out += p.separator;
      out += v.is_number() ? formatNumber(v.get<double>()) : std::string("?");
    }
    return out;
  }
  return {};
}

std::optional<Json> parseParam(const ParamDecl& p, std::string_view text, std::string& error) {
  const std::string name = paramName(p);
  switch (p.type) {
    case ParamType::Text:
      return Json(std::string(text));
    case ParamType::Flag: {
      const std::string_view t = trimmed(text);
      if (t == "1" || t == "true" || t == "on") return Json(true);
      if (t == "0" || t == "false" || t == "off") return Json(false);
      error = name + ": '" + std::string(text) + "' is not on or off (true, false)";
      return std::nullopt;
    }
    case ParamType::Choice: {
      const std::string_view t = trimmed(text);
      for (const std::string& c : p.choices)
        for (std::string_view n : choiceNames(c))
          if (t == n) return Json(canonicalChoice(c));
      error = name + ": '" + std::string(text) + "' is not one of " + choiceList(p);
      return std::nullopt;
    }
    case ParamType::Number: break;
  }
  // Numbers: split into `count` parts (or one for all).
  std::vector<std::string_view> parts;
  bool single = p.count == 1;  // one number typed (also for "2000" = 2000x2000)
  if (p.count == 1) {
    parts.push_back(text);
  } else {
    size_t start = 0;
    while (true) {
      const size_t sep = text.find(p.separator, start);
      parts.push_back(text.substr(start, sep == std::string_view::npos ? std::string_view::npos : sep - start));
      if (sep == std::string_view::npos) break;
      start = sep + 1;
    }
    if (parts.size() == 1 && p.oneForAll) {
      parts.assign(size_t(p.count), parts.front());
      single = true;
    }
  }
  const std::string quoted = "'" + std::string(text) + "'";
  const std::string shape = p.count == 1 ? std::string(p.integer ? "a whole number" : "a number")
                                         : (p.valueName.empty() ? std::to_string(p.count) + " numbers" : p.valueName);
  const std::string notShape = name + " takes " + shape + parenRange(p) + ", not " + quoted;
  if (int(parts.size()) != p.count) {
    error = notShape;
    return std::nullopt;
  }
  Json values = Json::array();
  for (int i = 0; i < p.count; ++i) {
    const std::string_view part = parts[size_t(i)];
    double v = 0.0;
    const NumberRead read = readNumber(part, p.integer, v);
    const std::string shown = single ? std::string(trimmed(part)) : std::string(trimmed(part)) + " in " + quoted;
    if (read == NumberRead::NotANumber || read == NumberRead::NotWhole) {
      error = notShape;
      return std::nullopt;
    }
    if (read == NumberRead::TooLarge || !inRange(p, i, v)) {
      error = name + ": " + shown + " is out of range" + parenRange(p);
      return std::nullopt;
    }
    if (p.ordered && i > 0 && v < values.back().get<double>()) {
      error = name + ": " + quoted + " is not in order (" + orderText(p) + ")";
      return std::nullopt;
    }
    if (p.integer) values.push_back(static_cast<long long>(v));
    else values.push_back(v);
  }
  return p.count == 1 ? values[0] : values;
}

bool checkParam(const ParamDecl& p, const Json& value, std::string& error) {
  const std::string name = paramName(p);
  switch (p.type) {
    case ParamType::Text:
      if (value.is_string()) return true;
      error = name + ": expected text";
      return false;
    case ParamType::Flag:
      if (value.is_boolean()) return true;
      error = name + ": expected true or false";
      return false;
    case ParamType::Choice:
      if (value.is_string()) {
        std::string unused;
        if (parseParam(p, value.get<std::string>(), unused)) return true;
        error = name + ": '" + value.get<std::string>() + "' is not one of " + choiceList(p);
        return false;
      }
      error = name + ": expected one of " + choiceList(p);
      return false;
    case ParamType::Number: break;
  }
  std::vector<double> numbers;
  if (p.count == 1 && value.is_number()) {
    numbers.push_back(value.get<double>());
  } else if (p.count > 1 && value.is_array() && int(value.size()) == p.count) {
    for (const Json& v : value) {
      if (!v.is_number()) break;
      numbers.push_back(v.get<double>());
    }
  }
  if (int(numbers.size()) != p.count) {
    error = name + ": expected " + (p.count == 1 ? std::string("a number") : std::to_string(p.count) + " numbers") +
            parenRange(p);
    return false;
  }
  for (int i = 0; i < p.count; ++i) {
    const double v = numbers[size_t(i)];
    if (!std::isfinite(v) || (p.integer && v != std::floor(v))) {
      error = name + ": " + formatNumber(v) + (p.integer ? " is not a whole number" : " is not a finite number") +
              parenRange(p);
      return false;
    }
    if (!inRange(p, i, v)) {
      error = name + ": " + formatNumber(v) + " is out of range" + parenRange(p);
      return false;
    }
    if (p.ordered && i > 0 && v < numbers[size_t(i) - 1]) {
      error = name + ": " + formatParamValue(p, Json(numbers)) + " is not in order (" + orderText(p) + ")";
      return false;
    }
  }
  return true;
}

double defaultNumber(const ParamDecl& p) { return p.defaultValue.is_number() ? p.defaultValue.get<double>() : 0.0; }

double clampParam(const ParamDecl& p, double v, std::vector<std::string>& warnings, std::string_view context) {
  const std::string prefix = context.empty() ? std::string() : std::string(context) + ": ";
  if (std::isnan(v)) {
    const double fallback = defaultNumber(p);
    warnings.push_back(prefix + p.label + " was not a number; using " + formatNumber(fallback));
    return fallback;
  }
  double c = std::clamp(v, p.min, p.max);
  if (p.integer) c = std::clamp(std::round(c), std::ceil(p.min), std::floor(p.max));
  if (c != v)
    warnings.push_back(prefix + p.label + " " + formatNumber(v) + " is out of range" + parenRange(p) + "; using " +
                       formatNumber(c));
  return c;
}

const ParamDecl* OperationDecl::find(std::string_view key) const {
  for (const ParamDecl& p : params)
    if (p.key == key) return &p;
  return nullptr;
}

const ParamDecl& OperationDecl::param(std::string_view key) const {
  if (const ParamDecl* p = find(key)) return *p;
  throw std::logic_error("operation '" + name + "' declares no parameter '" + std::string(key) + "'");
}

const ParamDecl& paramIn(const std::vector<ParamDecl>& params, std::string_view key) {
  for (const ParamDecl& p : params)
    if (p.key == key) return p;
  throw std::logic_error("no parameter '" + std::string(key) + "' is declared");
}

Json paramsJson(const OperationDecl& op, const Json& values) {
  Json out = Json::object();
  for (const ParamDecl& p : op.params) {
    if (values.is_object() && values.contains(p.key)) out[p.key] = values[p.key];
    else if (!p.defaultValue.is_null()) out[p.key] = p.defaultValue;
  }
  return out;
}

void appendParams(std::vector<ParamDecl>& to, const std::vector<ParamDecl>& more) {
  to.insert(to.end(), more.begin(), more.end());
}

}  // namespace hs

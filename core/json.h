#pragma once
// JSON for every library: nlohmann's json with members kept in the order
// they were written (ordered_json), so files diff cleanly, and numbers
// written in the shortest form that reads back to the same double.
//
// parseJson is strict: RFC 8259 (nlohmann refuses `1.`, `1.e5`, lone
// surrogates, trailing commas, NaN literals), plus no duplicate keys in an
// object and at most kMaxJsonDepth levels of nesting. Every error names the
// line and column ("line 3, column 14: duplicate key \"rate\"", with the
// JSON path of the object when it is not the document itself: "... in
// entities[2]").
//
// JsonReader reads values out of a parsed document and names the JSON path
// of the first bad one ("bindings[0].tracks[2].keys[5].t: expected a finite
// number"); jsonLocation turns such a path back into a line and column of
// the text it came from.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace hs {

using Json = nlohmann::ordered_json;

inline constexpr int kMaxJsonDepth = 256;

// nullopt with `error` ("line L, column C: what") when `text` is not one
// strict JSON value.
std::optional<Json> parseJson(std::string_view text, std::string& error);

// Pretty with `indent` spaces, or compact when indent < 0. Non-finite
// numbers are written as null (JSON has no NaN). Invalid UTF-8 in strings
// is replaced by U+FFFD rather than thrown.
std::string writeJson(const Json& value, int indent = 2);

// "line L, column C" of the value at `path` (as JsonReader names paths:
// `a.b[3].c`) in `text`, a document parseJson accepted; "" if there is no
// such value.
std::string jsonLocation(std::string_view text, std::string_view path);

// Path building: jsonPath("a", "b") = "a.b", jsonPath("", "b") = "b",
// jsonIndex("a", 3) = "a[3]".
std::string jsonPath(const std::string& parent, std::string_view key);
std::string jsonIndex(const std::string& parent, size_t index);

// "an object", "an array", "a string", "a number", "true or false", "null":
// what a value is, for messages ("expected an object, not an array").
const char* jsonTypeName(const Json& value);

// Typed reads that name the path of what is wrong. The first failure is
// kept in `error` ("path: what") and its path in errorPath(); later ones do
// not overwrite it, so a reader can go on and return once at the end, or
// stop at the first false. A value of the wrong type is named in the
// message ("expected an object, not an array").
class JsonReader {
 public:
  // `error` is cleared: the reader's first failure goes there, whatever a
  // caller's string held before.
  explicit JsonReader(std::string& error) : error_(error) { error_.clear(); }

  bool fail(const std::string& path, const std::string& what);
  bool failed() const { return !error_.empty(); }
  // The first failure's JSON path ("" for the document itself) and what
  // was wrong with the value there.
  const std::string& errorPath() const { return errorPath_; }
  const std::string& errorWhat() const { return errorWhat_; }

  // The member `key` of object `obj`, or nullptr (also when obj is not an object).
  static const Json* member(const Json& obj, std::string_view key);
  // The member `key` of `obj`; when there is none, nullptr and the failure
  // "path.key: missing".
  const Json* required(const Json& obj, const std::string& path, std::string_view key);

  bool object(const Json& v, const std::string& path);
  bool array(const Json& v, const std::string& path);
  bool number(const Json& v, const std::string& path, double& out);  // finite
  bool number(const Json& v, const std::string& path, double& out, double lo, double hi);
  bool integer(const Json& v, const std::string& path, int64_t& out, int64_t lo, int64_t hi);
  bool integer(const Json& v, const std::string& path, int& out, int lo, int hi);
  bool boolean(const Json& v, const std::string& path, bool& out);
  bool string(const Json& v, const std::string& path, std::string& out);
  // Exactly n finite numbers; `shape` names them in the message ("[x, y, z]").
  bool numbers(const Json& v, const std::string& path, double* out, size_t n, const char* shape = nullptr);

  // Optional members: absent (or null) leaves `out` as it is and succeeds.
  bool optNumber(const Json& obj, const std::string& path, std::string_view key, double& out);
  bool optInteger(const Json& obj, const std::string& path, std::string_view key, int& out, int lo, int hi);
  bool optBoolean(const Json& obj, const std::string& path, std::string_view key, bool& out);
  bool optString(const Json& obj, const std::string& path, std::string_view key, std::string& out);

 private:
  std::string& error_;
  std::string errorPath_, errorWhat_;
};

// A JsonReader's first failure on a document parsed from `text`, placed in
// the text: "bindings[0].t (line 3, column 9): expected a number, not a
// string" ("line 1, column 1: expected an object, not an array" for the
// document itself).
std::string jsonErrorIn(std::string_view text, const JsonReader& reader);

}  // namespace hs

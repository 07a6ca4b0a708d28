#pragma once
// A small JSON value, reader and writer: the sequencer has no Qt (DESIGN.md),
// and its data (sequences, farm manifests) must round-trip as text. Numbers
// are doubles written in the shortest form that reads back bit for bit.
// Objects keep their member order, so written files diff cleanly.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace hs::sequencer {

class JsonValue {
 public:
  using Array = std::vector<JsonValue>;
  using Object = std::vector<std::pair<std::string, JsonValue>>;

  JsonValue() = default;  // null
  JsonValue(std::nullptr_t) {}
  JsonValue(bool b) : v_(b) {}
  JsonValue(double d) : v_(d) {}
  JsonValue(int i) : v_(double(i)) {}
  JsonValue(int64_t i) : v_(double(i)) {}
  JsonValue(uint64_t i) : v_(double(i)) {}
  JsonValue(const char* s) : v_(std::string(s)) {}
  JsonValue(std::string s) : v_(std::move(s)) {}
  JsonValue(Array a) : v_(std::move(a)) {}
  JsonValue(Object o) : v_(std::move(o)) {}

  bool isNull() const { return std::holds_alternative<std::nullptr_t>(v_); }
  bool isBool() const { return std::holds_alternative<bool>(v_); }
  bool isNumber() const { return std::holds_alternative<double>(v_); }
  bool isString() const { return std::holds_alternative<std::string>(v_); }
  bool isArray() const { return std::holds_alternative<Array>(v_); }
  bool isObject() const { return std::holds_alternative<Object>(v_); }

  bool asBool() const { return std::get<bool>(v_); }
  double asNumber() const { return std::get<double>(v_); }
  const std::string& asString() const { return std::get<std::string>(v_); }
  const Array& asArray() const { return std::get<Array>(v_); }
  Array& asArray() { return std::get<Array>(v_); }
  const Object& asObject() const { return std::get<Object>(v_); }
  Object& asObject() { return std::get<Object>(v_); }

  // Object member by name; nullptr when absent or not an object.
  const JsonValue* find(std::string_view key) const;
  // Appends (or replaces) an object member.
  void set(std::string key, JsonValue value);

  bool operator==(const JsonValue&) const = default;

 private:
  std::variant<std::nullptr_t, bool, double, std::string, Array, Object> v_;
};

// Compact when indent < 0; otherwise pretty with `indent` spaces.
// Non-finite numbers are written as null (JSON has no NaN).
std::string writeJson(const JsonValue& value, int indent = 2);

// Strict RFC 8259 reader. On error, nullopt and `error` with the line and
// column ("line 3, column 14: expected ',' or '}'").
std::optional<JsonValue> readJson(std::string_view text, std::string& error);

}  // namespace hs::sequencer

#pragma once
// Errors as values. The terrain library never lets an exception cross its API:
// every operation that can fail on user input returns a Status or a Result<T>
// whose message names the file or the parameter and says what to do.
#include <optional>
#include <string>
#include <utility>

namespace hs::terrain {

struct Status {
  std::string error;  // empty = success
  bool ok() const { return error.empty(); }
  explicit operator bool() const { return ok(); }
  static Status success() { return {}; }
  static Status failure(std::string message) { return Status{std::move(message)}; }
};

// A value or an error message (std::expected is C++23; GCC 12 lacks it).
template <class T>
class Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit on purpose
  Result(Status status) : error_(std::move(status.error)) {
    if (error_.empty()) error_ = "unknown error";
  }
  static Result failure(std::string message) { return Result(Status::failure(std::move(message))); }

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const std::string& error() const { return error_; }
  T& value() { return *value_; }
  const T& value() const { return *value_; }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }
  T& operator*() { return *value_; }
  const T& operator*() const { return *value_; }
  T take() { return std::move(*value_); }

 private:
  std::optional<T> value_;
  std::string error_;
};

}  // namespace hs::terrain

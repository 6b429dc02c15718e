#pragma once
// Errors as values at boundaries: Status (ok or a message) and Result<T> (a value or a message).
// Propagating a failure is one line: `SLAM_TRY(call());` when the value is not needed, else
// `if (!r) return r.error();`.
#include <string>
#include <utility>
#include <variant>

namespace slam {

struct Error {
  std::string message;
};

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error e) : error_(std::move(e.message)), failed_(true) {}  // NOLINT: implicit by design
  static Status ok() { return {}; }

  bool is_ok() const { return !failed_; }
  explicit operator bool() const { return !failed_; }
  const std::string& message() const { return error_; }
  // The failure as an Error, to return from a function that returns Status or Result<U>.
  Error error() const { return Error{error_}; }

 private:
  std::string error_;
  bool failed_ = false;
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}  // NOLINT: implicit by design
  Result(Error e) : v_(std::move(e)) {}      // NOLINT: implicit by design

  bool is_ok() const { return v_.index() == 0; }
  explicit operator bool() const { return is_ok(); }
  T& value() { return std::get<0>(v_); }
  const T& value() const { return std::get<0>(v_); }
  T& operator*() { return value(); }
  const T& operator*() const { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  const std::string& message() const { return std::get<1>(v_).message; }
  Status status() const { return is_ok() ? Status{} : Status{std::get<1>(v_)}; }
  // The failure as an Error, to return from a function that returns Status or Result<U>.
  Error error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

}  // namespace slam

// Evaluates `expr` (a Status or Result) and returns its failure from the enclosing function, which
// returns Status or any Result<U>.
#define SLAM_TRY(expr)                                                                         \
  do {                                                                                         \
    if (auto slam_try_outcome_ = (expr); !slam_try_outcome_) return slam_try_outcome_.error(); \
  } while (0)

#pragma once
// Errors as values at boundaries: Status (ok or an Error) and Result<T> (a value or an Error).
// Propagating a failure is one line: `SLAM_TRY(call());` when the value is not needed, else
// `if (!r) return r.error();`.
// An Error says what went wrong in words (for people) and, where a caller acts on the cause, with a
// code (for code): each domain declares its own enum, as iceoryx does, and names its domain for
// it, found by argument-dependent lookup:
//   enum class MapError : uint16_t { InvalidRequest = 1, UnknownRobot };
//   constexpr ErrorDomain error_domain(MapError) { return ErrorDomain::Map; }
//   return Error{"unknown robot 'r1'", MapError::UnknownRobot};
//   if (status.is(MapError::UnknownRobot)) ...
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace slam {

// One value per domain that declares an error enum (0: a failure said only in words).
enum class ErrorDomain : uint16_t { None = 0, Map = 1 };

// True for an enum whose domain error_domain(E) names. (C++17 as well: the bridge's WebSocket unit
// is built as C++17.)
template <class E, class = void>
struct is_error_enum : std::false_type {};
template <class E>
struct is_error_enum<E, std::void_t<decltype(error_domain(std::declval<E>()))>> : std::is_enum<E> {};
template <class E>
inline constexpr bool is_error_enum_v = is_error_enum<E>::value;

// A domain and one of its enum's values; the default (no domain) is no code.
class ErrorCode {
 public:
  constexpr ErrorCode() = default;
  template <class E, class = std::enable_if_t<is_error_enum_v<E>>>
  constexpr ErrorCode(E e)  // NOLINT: implicit by design (Error{"text", MapError::Io})
      : domain_(error_domain(e)), value_(static_cast<uint32_t>(e)) {}

  constexpr ErrorDomain domain() const { return domain_; }
  constexpr uint32_t value() const { return value_; }
  constexpr bool operator==(const ErrorCode& o) const { return domain_ == o.domain_ && value_ == o.value_; }
  constexpr bool operator!=(const ErrorCode& o) const { return !(*this == o); }

 private:
  ErrorDomain domain_ = ErrorDomain::None;
  uint32_t value_ = 0;
};

struct Error {
  Error() = default;
  explicit Error(std::string text, ErrorCode cause = {}) : message(std::move(text)), code(cause) {}

  std::string message;
  ErrorCode code;  // none unless the failing function gives one
  template <class E, class = std::enable_if_t<is_error_enum_v<E>>>
  bool is(E e) const {
    return code == ErrorCode(e);
  }
};

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error e) : error_(std::move(e)), failed_(true) {}  // NOLINT: implicit by design
  static Status ok() { return {}; }

  bool is_ok() const { return !failed_; }
  explicit operator bool() const { return !failed_; }
  const std::string& message() const { return error_.message; }
  // The failure's code (none when ok or when the failure has none).
  ErrorCode code() const { return error_.code; }
  template <class E, class = std::enable_if_t<is_error_enum_v<E>>>
  bool is(E e) const {
    return failed_ && error_.is(e);
  }
  // The failure as an Error, to return from a function that returns Status or Result<U>.
  Error error() const { return error_; }

 private:
  Error error_;
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
  ErrorCode code() const { return is_ok() ? ErrorCode{} : std::get<1>(v_).code; }
  template <class E, class = std::enable_if_t<is_error_enum_v<E>>>
  bool is(E e) const {
    return !is_ok() && std::get<1>(v_).is(e);
  }
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

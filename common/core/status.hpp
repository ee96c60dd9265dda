#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <variant>

#include "common/core/check.hpp"

namespace fleetmap {

// Why an operation failed. Few codes, chosen for what a caller does differently:
// kInvalidArgument / kDataLoss mean the input is bad (tell the user), kNotFound a missing file,
// kResourceExhausted a configured limit, kUnavailable a middleware failure worth retrying.
enum class StatusCode {
  kOk = 0,
  kInvalidArgument,
  kNotFound,
  kDataLoss,
  kResourceExhausted,
  kUnavailable,
  kInternal,
};

const char* StatusCodeName(StatusCode code);

// The result of an operation that can fail on expected grounds (a bad file, a bad message, a
// DDS call that failed). The message names the input and what is wrong with it.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status Ok() { return Status(); }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  std::string ToString() const;

  // Returns a copy whose message is "<context>: <message>", to name the input at each layer.
  Status WithContext(const std::string& context) const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

std::ostream& operator<<(std::ostream& os, const Status& status);

inline Status InvalidArgumentError(std::string message) {
  return Status(StatusCode::kInvalidArgument, std::move(message));
}
inline Status NotFoundError(std::string message) {
  return Status(StatusCode::kNotFound, std::move(message));
}
inline Status DataLossError(std::string message) {
  return Status(StatusCode::kDataLoss, std::move(message));
}
inline Status ResourceExhaustedError(std::string message) {
  return Status(StatusCode::kResourceExhausted, std::move(message));
}
inline Status UnavailableError(std::string message) {
  return Status(StatusCode::kUnavailable, std::move(message));
}
inline Status InternalError(std::string message) {
  return Status(StatusCode::kInternal, std::move(message));
}

// A value or the Status saying why there is none. Accessing the value of an error is a bug.
template <typename T>
class [[nodiscard]] StatusOr {
 public:
  StatusOr(const T& value) : value_(value) {}        // NOLINT: implicit by design
  StatusOr(T&& value) : value_(std::move(value)) {}  // NOLINT: implicit by design
  StatusOr(const Status& status) : value_(status) {  // NOLINT: implicit by design
    FLEETMAP_CHECK(!status.ok(), "StatusOr needs a value or an error");
  }

  bool ok() const { return std::holds_alternative<T>(value_); }
  Status status() const { return ok() ? Status::Ok() : std::get<Status>(value_); }

  const T& value() const& { return Checked(), std::get<T>(value_); }
  T& value() & { return Checked(), std::get<T>(value_); }
  T&& value() && { return Checked(), std::move(std::get<T>(value_)); }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  void Checked() const { FLEETMAP_CHECK(ok(), "value() of an error StatusOr"); }

  std::variant<T, Status> value_;
};

}  // namespace fleetmap

// Returns from the enclosing function when `expr` (a Status) is an error.
#define FLEETMAP_RETURN_IF_ERROR(expr)                   \
  do {                                                   \
    ::fleetmap::Status fleetmap_status_ = (expr);        \
    if (!fleetmap_status_.ok()) return fleetmap_status_; \
  } while (false)

#define FLEETMAP_CONCAT_INNER(a, b) a##b
#define FLEETMAP_CONCAT(a, b) FLEETMAP_CONCAT_INNER(a, b)

// Declares `lhs` from a StatusOr expression, or returns its error from the enclosing function.
#define FLEETMAP_ASSIGN_OR_RETURN(lhs, expr) \
  FLEETMAP_ASSIGN_OR_RETURN_IMPL(FLEETMAP_CONCAT(fleetmap_statusor_, __LINE__), lhs, expr)
#define FLEETMAP_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                                   \
  if (!tmp.ok()) return tmp.status();                  \
  lhs = std::move(tmp).value()

// Error values for the precompute phase and status codes for the step phase.
//
// flexstress never throws. Precompute functions (meshing, assembly, reduction, influence
// matrices) return `Result<T>` or `Status`: either a value or an `Error` whose message names what
// is wrong and where (element id, node id, DOF, joint). Step functions (dynamics step, stress
// recovery, streaming fatigue) return a `StepStatus`, a plain enum that costs nothing to return.
// All three are [[nodiscard]]: ignoring a failure is a compiler warning.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "flexstress/core/assert.hpp"

namespace flexstress {

/// What kind of failure an Error reports. The message says where.
enum class ErrorCode : std::uint8_t {
  invalid_argument,    ///< A parameter is out of its domain (negative E, NaN coordinate, ...).
  invalid_mesh,        ///< Topology problem: missing node, duplicate id, link loop, ...
  degenerate_element,  ///< Zero-length beam, inverted or flat brick.
  singular_matrix,     ///< A system is singular after constraints (mechanism, rigid motion).
  not_converged,       ///< An iterative precompute (eigen solve, static equilibrium) failed.
  size_mismatch,       ///< A compile-time size does not fit the data (too few modes, ...).
  io_error,            ///< A file could not be opened, read or written.
  bad_file_format,     ///< A file is not what it claims to be (wrong magic, version, content).
};

/// Short lowercase name of an error code.
inline const char* to_string(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::invalid_argument: return "invalid argument";
    case ErrorCode::invalid_mesh: return "invalid mesh";
    case ErrorCode::degenerate_element: return "degenerate element";
    case ErrorCode::singular_matrix: return "singular matrix";
    case ErrorCode::not_converged: return "not converged";
    case ErrorCode::size_mismatch: return "size mismatch";
    case ErrorCode::io_error: return "i/o error";
    case ErrorCode::bad_file_format: return "bad file format";
  }
  return "unknown error";
}

/// A failure with a human-readable message that names what and where.
struct Error {
  ErrorCode code = ErrorCode::invalid_argument;
  std::string message;

  /// "<code>: <message>", ready to print.
  std::string what() const { return std::string(to_string(code)) + ": " + message; }
};

namespace detail {
/// What error() returns on success.
inline const Error& no_error() {
  static const Error none{ErrorCode::invalid_argument, "no error: the operation succeeded"};
  return none;
}
}  // namespace detail

/// Success, or an Error.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)) {}  // NOLINT: implicit by design

  static Status success() { return Status(); }

  bool ok() const noexcept { return !error_.has_value(); }
  explicit operator bool() const noexcept { return ok(); }

  /// The error; on success a placeholder saying there is none (so that a message argument
  /// evaluated whatever the outcome, as test macros do, is safe).
  const Error& error() const { return ok() ? detail::no_error() : *error_; }

 private:
  std::optional<Error> error_;
};

/// A value of type T, or an Error. Like std::expected (C++23), without exceptions.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}      // NOLINT: implicit by design
  Result(Error error) : error_(std::move(error)) {}  // NOLINT: implicit by design

  bool ok() const noexcept { return value_.has_value(); }
  explicit operator bool() const noexcept { return ok(); }

  const T& value() const& {
    FLEXSTRESS_ASSERT(ok(), "Result::value() called on an error; check ok() first");
    return *value_;
  }
  T& value() & {
    FLEXSTRESS_ASSERT(ok(), "Result::value() called on an error; check ok() first");
    return *value_;
  }
  T&& value() && {
    FLEXSTRESS_ASSERT(ok(), "Result::value() called on an error; check ok() first");
    return std::move(*value_);
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

  /// The error; on success a placeholder saying there is none (see Status::error).
  const Error& error() const& { return ok() ? detail::no_error() : *error_; }

  /// Drops the value, keeps an error (for forwarding an error to a caller of another type).
  Status status() const { return ok() ? Status() : Status(*error_); }

 private:
  std::optional<T> value_;
  std::optional<Error> error_;
};

namespace detail {
inline void append_part(std::string& out, const std::string& part) {
  out += part;
}
inline void append_part(std::string& out, const char* part) {
  out += part;
}
inline void append_part(std::string& out, std::string_view part) {
  out += part;
}
inline void append_part(std::string& out, char part) {
  out += part;
}
template <class T>
void append_part(std::string& out, const T& part) {
  if constexpr (std::is_integral_v<T>) {
    out += std::to_string(part);
  } else {
    static_assert(std::is_floating_point_v<T>, "make_error: parts must be text or numbers");
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", static_cast<double>(part));
    out += buffer;
  }
}
}  // namespace detail

/// Builds an Error from a code and message parts, e.g.
/// make_error(ErrorCode::degenerate_element, "hex8 element ", id, ": det J = ", d).
template <class... Parts>
Error make_error(ErrorCode code, const Parts&... parts) {
  std::string message;
  (detail::append_part(message, parts), ...);
  return Error{code, std::move(message)};
}

/// Outcome of one time step or one streaming update. Returned by value, never thrown.
enum class StepStatus : std::uint8_t {
  ok = 0,
  newton_not_converged,        ///< The implicit corrector hit its iteration limit.
  constraint_violation,        ///< Position or velocity constraints above tolerance after the step.
  non_finite_state,            ///< NaN or infinity in the state; the step was not taken.
  step_above_stability_limit,  ///< Explicit integrator: h exceeds its stability limit.
  invalid_input,               ///< A sample or command was NaN/infinite; nothing was changed.
  capacity_exceeded,           ///< A bounded buffer is full; nothing was lost, nothing was added.
  step_too_large,  ///< The implicit corrector diverged from a finite state; the step was not taken.
  /// With a Newton budget (accept_at_iteration_limit), or with Newton stalled within the joints'
  /// tolerance (keep_stalled_steps): the step was kept at its iteration limit without
  /// converging; StepStatistics::last_correction says how far from converged it is.
  budget_reached,
};

inline const char* to_string(StepStatus status) noexcept {
  switch (status) {
    case StepStatus::ok: return "ok";
    case StepStatus::newton_not_converged: return "Newton iteration did not converge";
    case StepStatus::constraint_violation: return "constraint violation above tolerance";
    case StepStatus::non_finite_state: return "non-finite state";
    case StepStatus::step_above_stability_limit: return "step size above the stability limit";
    case StepStatus::invalid_input: return "invalid (non-finite) input";
    case StepStatus::capacity_exceeded: return "capacity exceeded";
    case StepStatus::step_too_large: return "step too large for the motion (Newton diverged)";
    case StepStatus::budget_reached: return "kept at the Newton budget, not converged";
  }
  return "unknown status";
}

}  // namespace flexstress

// SPDX-License-Identifier: GPL-3.0-or-later
/// @file status.hpp
/// @brief Error reporting: every library entry point that can fail on bad input returns a Status.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace constrict {

/// What went wrong. Each code has its own CLI exit code (see exit_code()); the numbers are part of
/// the documented interface (docs/cli.md) and never change meaning.
enum class StatusCode {
  Ok = 0,
  InvalidArgument,  ///< a parameter out of range or an unknown option value
  FileNotFound,     ///< input file missing or unreadable
  WriteFailed,      ///< output could not be written
  ParseError,       ///< malformed number, wrong column count, unknown format
  EmptyInput,       ///< no points at all
  NonFinite,        ///< NaN or Inf coordinate
  Duplicate,        ///< two input points are identical
  TooFewPoints,     ///< fewer than 3 (2D) / 4 (3D) points
  Collinear,        ///< all points collinear (2D)
  Coplanar,         ///< all points coplanar (3D)
  Unsupported,      ///< valid request that this build or size limit cannot serve
  Incomplete,       ///< a result was written but does not pass through every point (lock with
                    ///< fallbacks disabled, or stopped early on request)
  Internal,         ///< a broken invariant (a bug): please report
};

/// Short stable name of a code, e.g. "Duplicate".
const char* to_string(StatusCode code) noexcept;

/// Process exit code used by the CLI for a status code (0 for Ok, distinct values otherwise).
int exit_code(StatusCode code) noexcept;

/// A number as a message shows it: the shortest text that reads back as @p v ("-1", "1e-10",
/// "inf"), where std::to_string's "%f" gave "-1.000000" and "0.000000".
std::string number_text(double v);

/// A status code plus a one-line human readable message.
class Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}
  static Status ok() { return {}; }

  bool is_ok() const noexcept { return code_ == StatusCode::Ok; }
  explicit operator bool() const noexcept { return is_ok(); }
  StatusCode code() const noexcept { return code_; }
  const std::string& message() const noexcept { return message_; }

 private:
  StatusCode code_ = StatusCode::Ok;
  std::string message_;
};

/// Thrown only for broken invariants (bugs), never for bad input.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace constrict

/// Cheap always-on invariant check: throws constrict::InternalError with file and line.
#define CONSTRICT_CHECK(cond, msg)                                                              \
  do {                                                                                          \
    if (!(cond))                                                                                \
      throw ::constrict::InternalError(std::string(__FILE__) + ":" + std::to_string(__LINE__) + \
                                       ": " + (msg));                                           \
  } while (0)

#ifdef NDEBUG
#define CONSTRICT_ASSERT(cond, msg) ((void)0)
#else
#define CONSTRICT_ASSERT(cond, msg) CONSTRICT_CHECK(cond, msg)
#endif

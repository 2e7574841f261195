// SPDX-License-Identifier: GPL-3.0-or-later
#include "constrict/status.hpp"

#include <charconv>
#include <string>

namespace constrict {

std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

const char* to_string(StatusCode code) noexcept {
  switch (code) {
    case StatusCode::Ok: return "Ok";
    case StatusCode::InvalidArgument: return "InvalidArgument";
    case StatusCode::FileNotFound: return "FileNotFound";
    case StatusCode::WriteFailed: return "WriteFailed";
    case StatusCode::ParseError: return "ParseError";
    case StatusCode::EmptyInput: return "EmptyInput";
    case StatusCode::NonFinite: return "NonFinite";
    case StatusCode::Duplicate: return "Duplicate";
    case StatusCode::TooFewPoints: return "TooFewPoints";
    case StatusCode::Collinear: return "Collinear";
    case StatusCode::Coplanar: return "Coplanar";
    case StatusCode::Unsupported: return "Unsupported";
    case StatusCode::Incomplete: return "Incomplete";
    case StatusCode::Internal: return "Internal";
  }
  return "Unknown";
}

// Exit codes (docs/cli.md): 1 is never used for a known defect, command-line usage errors are
// InvalidArgument (2), 70 (EX_SOFTWARE) marks a bug.
int exit_code(StatusCode code) noexcept {
  switch (code) {
    case StatusCode::Ok: return 0;
    case StatusCode::InvalidArgument: return 2;
    case StatusCode::FileNotFound: return 3;
    case StatusCode::WriteFailed: return 4;
    case StatusCode::ParseError: return 5;
    case StatusCode::EmptyInput: return 6;
    case StatusCode::NonFinite: return 7;
    case StatusCode::Duplicate: return 8;
    case StatusCode::TooFewPoints: return 9;
    case StatusCode::Collinear: return 10;
    case StatusCode::Coplanar: return 11;
    case StatusCode::Unsupported: return 12;
    case StatusCode::Incomplete: return 13;
    case StatusCode::Internal: return 70;
  }
  return 1;
}

}  // namespace constrict

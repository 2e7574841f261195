// SPDX-License-Identifier: GPL-3.0-or-later
// Names and presets of the 2D options (constrict.hpp): the library's vocabulary, which the CLI
// and the Python module only parse and print.
#include "constrict/constrict.hpp"

namespace constrict {

const char* to_string(Fallback f) noexcept {
  switch (f) {
    case Fallback::Auto: return "auto";
    case Fallback::Gamma0: return "gamma0";
    case Fallback::Degree4: return "degree4";
    case Fallback::None: return "none";
  }
  return "?";
}

bool fallback_from_name(const std::string& name, Fallback& out) noexcept {
  for (Fallback f : {Fallback::Auto, Fallback::Gamma0, Fallback::Degree4, Fallback::None})
    if (name == to_string(f)) {
      out = f;
      return true;
    }
  return false;
}

Status Constrict2Options::from_preset(const std::string& name, Constrict2Options& out) {
  if (name == "default") out = Constrict2Options{};
  else if (name == "paper") out = paper();
  else return {StatusCode::InvalidArgument, "unknown 2D preset '" + name + "' (use default or paper)"};
  return Status::ok();
}

}  // namespace constrict

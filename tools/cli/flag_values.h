// Numeric flag values for the tools CLIs: the whole string must parse, otherwise a UsageError names
// the flag and the value.
#pragma once

#include <stdexcept>
#include <string>

#include "core/util/cli.h"

namespace lc2wf {

inline int int_flag(const std::string& flag, const std::string& v) {
  try {
    size_t used = 0;
    const int x = std::stoi(v, &used);
    if (used == v.size()) return x;
  } catch (const std::exception&) {
  }
  throw UsageError(flag + " expects an integer, got '" + v + "'");
}

inline double number_flag(const std::string& flag, const std::string& v) {
  try {
    size_t used = 0;
    const double x = std::stod(v, &used);
    if (used == v.size()) return x;
  } catch (const std::exception&) {
  }
  throw UsageError(flag + " expects a number, got '" + v + "'");
}

}  // namespace lc2wf

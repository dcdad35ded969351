// printf-style formatting of one number into a std::string, for the Markdown and HTML tables.
#pragma once

#include <cstdio>
#include <string>

namespace lc2wf {

inline std::string format_number(const char* printf_format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

}  // namespace lc2wf

// One number as text through a printf format ("%.3g": 0.125 -> "0.125"), for the
// commands' tables and the charts' notes.
#pragma once

#include <cstdio>
#include <string>

namespace invfree {

inline std::string format_number(double value, const char* printf_format = "%.3g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

}  // namespace invfree

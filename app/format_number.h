// Numbers as text for the commands' tables, messages and the charts' notes.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace invfree {

inline std::string format_number(double value, const char* printf_format = "%.3g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

// A number for people to read: from 1000 up (in magnitude) a whole number with thousands
// separators ("336,935"), below that three significant digits ("0.125", "10").
inline std::string format_for_people(double value) {
  if (!std::isfinite(value) || std::abs(value) < 1000.0 || std::abs(value) >= 1e15)
    return format_number(value, "%.3g");
  const std::string digits = format_number(std::abs(value), "%.0f");
  std::string grouped;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped += ',';
    grouped += digits[i];
  }
  return (value < 0.0 ? "-" : "") + grouped;
}

}  // namespace invfree

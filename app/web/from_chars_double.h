// Force-included into invfree_scene_io in the web build only (app/web/CMakeLists.txt):
// emscripten 3.1.6's libc++ has integer std::from_chars but no floating-point one, which
// the shape files' readers (core/scene_io/mesh_file.cpp, svg_outline.cpp) call. This is
// the one for double, in std:: so that their `std::from_chars(first, last, x)` finds it,
// with from_chars's rules kept where strtod differs: no leading whitespace or '+', no
// "0x" hexadecimal (from_chars reads the "0" only), out of range reported as
// result_out_of_range. The page has only the "C" locale, so strtod's decimal point is '.'.
// Remove it once those files do as core/scene_io/key_table.cpp does for to_chars (an
// __EMSCRIPTEN__ branch), or once emscripten's libc++ has it.
#pragma once

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <string>

_LIBCPP_BEGIN_NAMESPACE_STD
inline from_chars_result from_chars(const char* first, const char* last, double& value) {
  const std::string text(first, last);
  const char* digits = text.c_str();
  if (*digits == '-') ++digits;
  if (*digits == '\0' || *digits == '+' || *digits == '-' || *digits == ' ' || *digits == '\t' ||
      *digits == '\n' || *digits == '\r' || *digits == '\v' || *digits == '\f')
    return {first, errc::invalid_argument};
  if (digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
    value = text[0] == '-' ? -0.0 : 0.0;
    return {first + (digits + 1 - text.c_str()), errc()};
  }
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return {first, errc::invalid_argument};
  const char* ptr = first + (end - text.c_str());
  if (errno == ERANGE) return {ptr, errc::result_out_of_range};
  value = x;
  return {ptr, errc()};
}
_LIBCPP_END_NAMESPACE_STD

#include "scene_io/toml_guard.h"

#include <algorithm>
#include <cstdio>

namespace invfree {

namespace {

bool tomlpp_unsafe(char32_t c) {
  return (c >= 0xA1 && c <= 0x499) || (c >= 0x2C8E && c <= 0x3087 && c != 0x3000) ||
         (c >= 0xFB26 && c <= 0xFEFE);
}

// The code point of the UTF-8 sequence at t[i] and its length; 0 for an invalid or
// truncated sequence (toml++ rejects those before classifying anything).
size_t utf8_at(std::string_view t, size_t i, char32_t* cp) {
  const auto b = [&](size_t k) { return static_cast<unsigned char>(t[k]); };
  const unsigned char c = b(i);
  const size_t n = c < 0x80           ? 1
                   : (c >> 5) == 0x6  ? 2
                   : (c >> 4) == 0xE  ? 3
                   : (c >> 3) == 0x1E ? 4
                                      : 0;
  if (n == 0 || i + n > t.size()) return 0;
  char32_t v = n == 1 ? c : n == 2 ? (c & 0x1F) : n == 3 ? (c & 0x0F) : (c & 0x07);
  for (size_t k = 1; k < n; ++k) {
    if ((b(i + k) & 0xC0) != 0x80) return 0;
    v = (v << 6) | (b(i + k) & 0x3F);
  }
  *cp = v;
  return n;
}

std::string unicode_escape(char32_t c) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "\\u%04X", static_cast<unsigned>(c));
  return buf;
}

bool has_unsafe(std::string_view text) {
  for (size_t i = 0; i < text.size(); ++i) {
    char32_t cp = 0;
    if (static_cast<unsigned char>(text[i]) >= 0x80 && utf8_at(text, i, &cp) > 1 &&
        tomlpp_unsafe(cp))
      return true;
  }
  return false;
}

// Literal-string content as basic-string content: backslashes and quotes escaped, unsafe
// code points as \uXXXX, everything else (line breaks of a multi-line string too) as is.
std::string literal_as_basic(std::string_view content) {
  std::string out;
  for (size_t i = 0; i < content.size();) {
    char32_t cp = 0;
    const size_t n = std::max<size_t>(utf8_at(content, i, &cp), 1);
    if (n > 1 && tomlpp_unsafe(cp)) {
      out += unicode_escape(cp);
    } else {
      if (content[i] == '\\' || content[i] == '"') out += '\\';
      out.append(content.substr(i, n));
    }
    i += n;
  }
  return out;
}

bool bare_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

// One pass over the text: where it is (outside strings, in a comment, in a basic string),
// the rewritten text so far and the line reached. Each step returns "" or the reason the
// text cannot be made safe.
struct SafeTextScanner {
  enum class State { Normal, Comment, Basic, MultiBasic };
  std::string_view t;
  std::string* out;
  int* line;
  State state = State::Normal;
  int dots = 0;  // in the current dotted run
  size_t i = 0;

  bool at(size_t k, std::string_view s) const { return t.substr(k, s.size()) == s; }
  bool non_ascii(size_t k) const {
    return k < t.size() && static_cast<unsigned char>(t[k]) >= 0x80;
  }
  void count_lines(size_t from, size_t to) {
    for (size_t k = from; k < to; ++k) *line += t[k] == '\n';
  }
  void copy(size_t from, size_t to) {  // copies t[from, to), counting lines
    count_lines(from, to);
    out->append(t.substr(from, to - from));
  }

  // A literal string, copied whole or -- when it holds an unsafe code point -- rewritten as
  // a basic string. It ends at ''' (up to two more quotes belong to the content) or at
  // ' / a line break.
  void literal_string() {
    const bool multi = at(i, "'''");
    const size_t open = multi ? 3 : 1;
    size_t end = i + open;
    while (end < t.size() && !(multi ? at(end, "'''") : (t[end] == '\'' || t[end] == '\n')))
      ++end;
    size_t content_end = end, stop = end;
    if (multi && end < t.size()) {
      size_t quotes = 3;
      while (end + quotes < t.size() && t[end + quotes] == '\'' && quotes < 5) ++quotes;
      content_end = end + quotes - 3;
      stop = end + quotes;
    } else if (!multi && end < t.size() && t[end] == '\'') {
      stop = end + 1;
    }
    const bool closed = stop > content_end;
    const std::string_view content = t.substr(i + open, content_end - (i + open));
    if (has_unsafe(content)) {
      const char* quotes = multi ? "\"\"\"" : "\"";
      count_lines(i, stop);
      *out += quotes;
      *out += literal_as_basic(content);
      if (closed) *out += quotes;
    } else {
      copy(i, stop);
    }
    i = stop;
  }

  // Outside strings and comments.
  std::string normal() {
    const char c = t[i];
    if (at(i, "'''") || c == '\'') {
      literal_string();
      return "";
    }
    if (at(i, "\"\"\"")) {
      copy(i, i + 3);
      i += 3;
      state = State::MultiBasic;
      return "";
    }
    // A dotted run is made of bare-key characters, blanks, strings (quoted key parts,
    // skipped above and below) and dots; anything else ends it.
    if (c == '.') {
      if (++dots > 1) return "a dotted key with more than two parts (a scene needs section.key)";
    } else if (!(bare_key_char(c) || c == ' ' || c == '\t' || c == '"')) {
      dots = 0;
    }
    if (c == '#') state = State::Comment;
    if (c == '"') state = State::Basic;
    if (non_ascii(i)) return "non-ASCII character outside a string or comment";
    copy(i, i + 1);
    ++i;
    return "";
  }

  // After a backslash toml++ skips blanks (and, in a multi-line string, line breaks),
  // testing each character for whitespace; a non-ASCII one there is never valid.
  std::string escape() {
    size_t j = i + 1;
    while (j < t.size() && (t[j] == ' ' || t[j] == '\t' ||
                            (state == State::MultiBasic && (t[j] == '\n' || t[j] == '\r'))))
      ++j;
    if (non_ascii(j)) {
      count_lines(i, j);
      return "non-ASCII character after a backslash in a string";
    }
    const size_t upto = std::min(t.size(), j + 1);  // the escaped character goes too
    copy(i, upto);
    i = upto;
    return "";
  }

  // In a comment or a basic string: unsafe code points are replaced.
  std::string in_text() {
    const char c = t[i];
    char32_t cp = 0;
    const size_t n = non_ascii(i) ? std::max<size_t>(utf8_at(t, i, &cp), 1) : 1;
    if (n > 1 && tomlpp_unsafe(cp)) {
      *out += state == State::Comment ? std::string("?") : unicode_escape(cp);
      i += n;
      return "";
    }
    if (state == State::Comment) {
      if (c == '\n') state = State::Normal;
    } else if (c == '\\') {
      return escape();
    } else if (state == State::Basic && (c == '"' || c == '\n')) {
      state = State::Normal;
    } else if (state == State::MultiBasic && at(i, "\"\"\"")) {
      size_t quotes = 3;
      while (i + quotes < t.size() && t[i + quotes] == '"' && quotes < 5) ++quotes;
      copy(i, i + quotes);
      i += quotes;
      state = State::Normal;
      return "";
    }
    copy(i, i + n);
    i += n;
    return "";
  }
};

}  // namespace

std::string tomlpp_safe_text(std::string_view t, std::string* out, int* line) {
  out->clear();
  out->reserve(t.size() + 16);
  *line = 1;
  SafeTextScanner scan{t, out, line};
  scan.i = scan.at(0, "\xEF\xBB\xBF") ? 3 : 0;  // a byte-order mark is fine
  scan.copy(0, scan.i);
  while (scan.i < t.size()) {
    const std::string problem =
        scan.state == SafeTextScanner::State::Normal ? scan.normal() : scan.in_text();
    if (!problem.empty()) return problem;
  }
  return "";
}

}  // namespace invfree

#include "scene_io/scene_file.h"

#include <sys/stat.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace invfree {

namespace {

// Scene files larger than this are certainly not scenes (the built-in ones are < 1 kB);
// refusing them keeps `--scene /dev/zero` or a stray video from eating memory.
constexpr std::uintmax_t kMaxSceneFileBytes = 1 << 20;

// User text quoted in an error (a key, a value, a path) with control characters escaped
// and long text cut, so every error stays one readable line.
std::string printable(std::string_view text, size_t max_chars = 80) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (out.size() >= max_chars && (c & 0xC0) != 0x80) {  // never cut inside a UTF-8 sequence
      out += "...";
      break;
    }
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

// A user's string value in double quotes, with quotes and backslashes escaped.
std::string quoted(std::string_view text) {
  std::string escaped;
  for (char c : text) {
    if (c == '"' || c == '\\') escaped += '\\';
    escaped += c;
  }
  std::string out(1, '"');  // (not "\"" + ...: GCC 12 warns falsely on that form)
  out += printable(escaped);
  out += '"';
  return out;
}

bool has_control_characters(std::string_view text) {
  return std::any_of(text.begin(), text.end(), [](char c) {
    const unsigned char u = static_cast<unsigned char>(c);
    return u < 0x20 || u == 0x7f;
  });
}

// ---- a guard in front of toml++ 3.3 ------------------------------------------------------
// toml++ 3.3.0 (Debian 12) reaches __builtin_unreachable() -- undefined behaviour, found by
// our fuzzer -- when it asks whether a code point in U+00A1..U+0499, U+2C8E..U+3087 (but
// U+3000) or U+FB26..U+FEFE is whitespace (upstream issues #190 and #295); its parser
// asks that of characters outside strings, after a backslash in a string, and while
// reporting some errors. So toml++ never sees such a code point: in a basic string it
// becomes the equivalent \uXXXX escape, a literal string holding one is rewritten as the
// equivalent basic string, in a comment it becomes '?', and anywhere else (where no valid
// scene has a non-ASCII character) the text is refused. Valid TOML keeps its meaning.

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

// Returns "" and the text for toml++ in *out, or a reason and its line in *line.
std::string tomlpp_safe_text(std::string_view t, std::string* out, int* line) {
  enum class State { Normal, Comment, Basic, MultiBasic } state = State::Normal;
  out->clear();
  out->reserve(t.size() + 16);
  *line = 1;
  auto at = [&](size_t i, std::string_view s) { return t.substr(i, s.size()) == s; };
  auto non_ascii = [&](size_t i) {
    return i < t.size() && static_cast<unsigned char>(t[i]) >= 0x80;
  };
  auto copy = [&](size_t from, size_t to) {  // copies t[from, to), counting lines
    for (size_t k = from; k < to; ++k) *line += t[k] == '\n';
    out->append(t.substr(from, to - from));
  };
  size_t i = at(0, "\xEF\xBB\xBF") ? 3 : 0;  // a byte-order mark is fine
  copy(0, i);
  while (i < t.size()) {
    const char c = t[i];
    if (state == State::Normal) {
      if (at(i, "'''") || c == '\'') {
        // A literal string, copied whole or -- when it holds an unsafe code point --
        // rewritten as a basic string. It ends at ''' (up to two more quotes belong to
        // the content) or at ' / a line break.
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
          for (size_t k = i; k < stop; ++k) *line += t[k] == '\n';
          *out += quotes;
          *out += literal_as_basic(content);
          if (closed) *out += quotes;
        } else {
          copy(i, stop);
        }
        i = stop;
        continue;
      }
      if (at(i, "\"\"\"")) {
        copy(i, i + 3);
        i += 3;
        state = State::MultiBasic;
        continue;
      }
      if (c == '#') state = State::Comment;
      if (c == '"') state = State::Basic;
      if (non_ascii(i)) return "non-ASCII character outside a string or comment";
      copy(i, i + 1);
      ++i;
      continue;
    }
    // In a comment or a basic string: unsafe code points are replaced.
    char32_t cp = 0;
    const size_t n = non_ascii(i) ? std::max<size_t>(utf8_at(t, i, &cp), 1) : 1;
    if (n > 1 && tomlpp_unsafe(cp)) {
      *out += state == State::Comment ? std::string("?") : unicode_escape(cp);
      i += n;
      continue;
    }
    if (state == State::Comment) {
      if (c == '\n') state = State::Normal;
    } else if (c == '\\') {
      // After a backslash toml++ skips blanks (and, in a multi-line string, line breaks),
      // testing each character for whitespace; a non-ASCII one there is never valid.
      size_t j = i + 1;
      while (j < t.size() && (t[j] == ' ' || t[j] == '\t' ||
                              (state == State::MultiBasic && (t[j] == '\n' || t[j] == '\r'))))
        ++j;
      if (non_ascii(j)) {
        for (size_t k = i; k < j; ++k) *line += t[k] == '\n';
        return "non-ASCII character after a backslash in a string";
      }
      const size_t upto = std::min(t.size(), j + 1);  // the escaped character goes too
      copy(i, upto);
      i = upto;
      continue;
    } else if (state == State::Basic && (c == '"' || c == '\n')) {
      state = State::Normal;
    } else if (state == State::MultiBasic && at(i, "\"\"\"")) {
      size_t quotes = 3;
      while (i + quotes < t.size() && t[i + quotes] == '"' && quotes < 5) ++quotes;
      copy(i, i + quotes);
      i += quotes;
      state = State::Normal;
      continue;
    }
    copy(i, i + n);
    i += n;
  }
  return "";
}

// ---- typed readers: return "" or a reason -------------------------------------------

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

std::string read_number(const toml::node& n, double& out) {
  if (auto v = n.value<double>(); v && (n.is_integer() || n.is_floating_point())) {
    out = *v;
    if (!std::isfinite(out)) return "must be a finite number";
    return "";
  }
  return "expected a number, got " + type_name(n);
}

std::string read_int(const toml::node& n, long long& out) {
  if (n.is_integer()) {
    out = n.as_integer()->get();
    return "";
  }
  if (n.is_floating_point()) {
    const double d = n.as_floating_point()->get();
    if (std::isfinite(d) && d == std::floor(d) && std::abs(d) < 1e15) {
      out = static_cast<long long>(d);
      return "";
    }
  }
  return "expected an integer, got " + type_name(n);
}

std::string read_bool(const toml::node& n, bool& out) {
  if (!n.is_boolean()) return "expected true or false, got " + type_name(n);
  out = n.as_boolean()->get();
  return "";
}

std::string read_string(const toml::node& n, std::string& out) {
  if (!n.is_string()) return "expected a string, got " + type_name(n);
  out = n.as_string()->get();
  return "";
}

std::string read_vec2(const toml::node& n, Vec2& out) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) return "expected an array of two numbers, e.g. [0.0, -9.81]";
  for (int k = 0; k < 2; ++k)
    if (auto r = read_number(*a->get(k), out[k]); !r.empty())
      return "element " + std::to_string(k) + ": " + r;
  return "";
}

std::string set_double(const toml::node& n, double& field) {
  return read_number(n, field);
}

std::string set_int(const toml::node& n, int& field, long long lo, long long hi) {
  long long v = 0;
  if (auto r = read_int(n, v); !r.empty()) return r;
  if (v < lo || v > hi)
    return "must be between " + std::to_string(lo) + " and " + std::to_string(hi);
  field = static_cast<int>(v);
  return "";
}

template <class Enum>
std::string set_enum(const toml::node& n, Enum& field,
                     std::optional<Enum> (*parse)(std::string_view), const char* choices) {
  std::string s;
  if (auto r = read_string(n, s); !r.empty()) return r;
  auto v = parse(s);
  if (!v) return "unknown value " + quoted(s) + " (expected one of " + choices + ")";
  field = *v;
  return "";
}

std::optional<MassMode> mass_from_name(std::string_view s) {
  if (s == "uniform") return MassMode::Uniform;
  if (s == "lumped") return MassMode::Lumped;
  return std::nullopt;
}

// ---- the key table --------------------------------------------------------------------

using Setter = std::string (*)(SceneDef&, const toml::node&);
struct KeySpec {
  const char* section;
  const char* key;
  Setter set;
};

const KeySpec kKeys[] = {
    {"mesh", "side", [](SceneDef& s, const toml::node& n) { return set_double(n, s.side); }},
    {"mesh", "n_seg",
     [](SceneDef& s, const toml::node& n) { return set_int(n, s.n_seg, 1, kMaxSegments); }},
    {"mesh", "density", [](SceneDef& s, const toml::node& n) { return set_double(n, s.density); }},
    {"mesh", "mass",
     [](SceneDef& s, const toml::node& n) {
       return set_enum<MassMode>(n, s.mass, mass_from_name, "\"uniform\", \"lumped\"");
     }},
    {"mesh", "jitter", [](SceneDef& s, const toml::node& n) { return set_double(n, s.jitter); }},
    {"mesh", "seed",
     [](SceneDef& s, const toml::node& n) {
       long long v = 0;
       if (auto r = read_int(n, v); !r.empty()) return r;
       if (v < 0) return std::string("must be >= 0");
       s.seed = static_cast<std::uint64_t>(v);
       return std::string();
     }},
    {"material", "model",
     [](SceneDef& s, const toml::node& n) {
       return set_enum<Model>(n, s.model, model_from_name,
                              "\"neo-hookean\", \"linear\", \"arap\", \"stable-neo-hookean\"");
     }},
    // E, nu, mu, lambda are handled together by set_material.
    {"material", "E", nullptr},
    {"material", "nu", nullptr},
    {"material", "mu", nullptr},
    {"material", "lambda", nullptr},
    {"time", "h", [](SceneDef& s, const toml::node& n) { return set_double(n, s.h); }},
    {"time", "tol", [](SceneDef& s, const toml::node& n) { return set_double(n, s.tol); }},
    {"time", "max_newton",
     [](SceneDef& s, const toml::node& n) { return set_int(n, s.max_newton, 1, 100000); }},
    {"solver", "projection",
     [](SceneDef& s, const toml::node& n) {
       return set_enum<HessianProjection>(n, s.projection, projection_from_name,
                                          "\"diagonal\", \"full\", \"none\"");
     }},
    {"solver", "inversion_filter",
     [](SceneDef& s, const toml::node& n) { return read_bool(n, s.inversion_filter); }},
    {"solver", "step_expansion",
     [](SceneDef& s, const toml::node& n) { return read_bool(n, s.step_expansion); }},
    {"solver", "friction_crossing_stop",
     [](SceneDef& s, const toml::node& n) { return read_bool(n, s.friction_crossing_stop); }},
    {"solver", "integrator",
     [](SceneDef& s, const toml::node& n) {
       return set_enum<Integrator>(n, s.integrator, integrator_from_name,
                                   "\"implicit-euler\", \"symplectic-euler\"");
     }},
    {"solver", "linear_solver",
     [](SceneDef& s, const toml::node& n) {
       return set_enum<LinearSolverKind>(n, s.linear_solver, linear_solver_from_name,
                                         "\"auto\", \"ldlt\", \"cholmod\", \"pcg\"");
     }},
    {"initial", "velocity",
     [](SceneDef& s, const toml::node& n) { return read_vec2(n, s.initial_velocity); }},
    {"gravity", "enabled",
     [](SceneDef& s, const toml::node& n) { return read_bool(n, s.has_gravity); }},
    {"gravity", "g", [](SceneDef& s, const toml::node& n) { return read_vec2(n, s.gravity); }},
    {"ground", "enabled",
     [](SceneDef& s, const toml::node& n) { return read_bool(n, s.has_ground); }},
    {"ground", "y", [](SceneDef& s, const toml::node& n) { return set_double(n, s.ground_y); }},
    {"ground", "friction",
     [](SceneDef& s, const toml::node& n) { return set_double(n, s.friction); }},
    {"ceiling", "enabled",
     [](SceneDef& s, const toml::node& n) { return read_bool(n, s.has_ceiling); }},
    {"ceiling", "y", [](SceneDef& s, const toml::node& n) { return set_double(n, s.ceiling_y); }},
    {"ceiling", "velocity",
     [](SceneDef& s, const toml::node& n) { return set_double(n, s.ceiling_velocity); }},
    {"ceiling", "stop",
     [](SceneDef& s, const toml::node& n) { return set_double(n, s.ceiling_stop); }},
    {"barrier", "dhat", [](SceneDef& s, const toml::node& n) { return set_double(n, s.dhat); }},
    {"barrier", "kappa", [](SceneDef& s, const toml::node& n) { return set_double(n, s.kappa); }},
};

const char* const kSections[] = {"mesh",    "material", "time",    "solver", "initial",
                                 "gravity", "ground",   "ceiling", "barrier"};

// Sections whose presence switches a term on.
bool* term_flag(SceneDef& s, std::string_view section) {
  if (section == "gravity") return &s.has_gravity;
  if (section == "ground") return &s.has_ground;
  if (section == "ceiling") return &s.has_ceiling;
  return nullptr;
}

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best.empty() ? "" : " (did you mean \"" + best + "\"?)";
}

std::vector<std::string> keys_of(std::string_view section) {
  std::vector<std::string> out;
  for (const auto& k : kKeys)
    if (section == k.section) out.emplace_back(k.key);
  return out;
}

const KeySpec* find_key(std::string_view section, std::string_view key) {
  for (const auto& k : kKeys)
    if (section == k.section && key == k.key) return &k;
  return nullptr;
}

bool is_section(std::string_view s) {
  return std::find(std::begin(kSections), std::end(kSections), s) != std::end(kSections);
}

std::string unknown_section_error(std::string_view section) {
  return "unknown section" + did_you_mean(section, {std::begin(kSections), std::end(kSections)}) +
         " (sections: mesh, material, time, solver, initial, gravity, ground, ceiling, barrier)";
}

struct MaterialInput {
  std::optional<double> E, nu, mu, lambda;
};

// Applies E/nu or mu/lambda; a value given alone keeps the other of its pair.
// Returns "" or "key: reason".
std::string set_material(SceneDef& s, const MaterialInput& in) {
  if ((in.E || in.nu) && (in.mu || in.lambda))
    return std::string(in.E ? "material.E" : "material.nu") +
           ": give either E and nu or mu and lambda, not both";
  if (in.E && !(*in.E > 0.0)) return "material.E: must be > 0";
  if (in.nu && !(*in.nu >= 0.0 && *in.nu < 0.5)) return "material.nu: must be in [0, 0.5)";
  if (in.mu && !(*in.mu > 0.0)) return "material.mu: must be > 0";
  if (in.lambda && !(*in.lambda >= 0.0)) return "material.lambda: must be >= 0";
  if (in.E || in.nu) {
    double E = 0.0, nu = 0.0;
    young_poisson_from_lame(s.lame, &E, &nu);
    s.lame = lame_from_young_poisson(in.E.value_or(E), in.nu.value_or(nu));
    if (!std::isfinite(s.lame.mu) || !std::isfinite(s.lame.lambda))
      return std::string(in.E ? "material.E" : "material.nu") +
             ": too large (mu and lambda must be finite)";
  } else {
    if (in.mu) s.lame.mu = *in.mu;
    if (in.lambda) s.lame.lambda = *in.lambda;
  }
  return "";
}

// Applies one key (already known to exist). Returns "" or a reason.
std::string apply_key(SceneDef& s, std::string_view section, const KeySpec& spec,
                      const toml::node& value, MaterialInput* material) {
  if (bool* flag = term_flag(s, section); flag && std::string_view(spec.key) != "enabled")
    *flag = true;
  if (spec.set) return spec.set(s, value);
  double v = 0.0;
  if (auto r = read_number(value, v); !r.empty()) return r;
  const std::string_view k = spec.key;
  (k == "E"    ? material->E
   : k == "nu" ? material->nu
   : k == "mu" ? material->mu
               : material->lambda) = v;
  return "";
}

std::string located(const std::string& source, int line, const std::string& what) {
  const std::string where = printable(source, 200);
  return line > 0 ? where + ":" + std::to_string(line) + ": " + what : where + ": " + what;
}

}  // namespace

SceneLoad parse_scene_toml(std::string_view text, const std::string& source) {
  SceneLoad out;
  if (text.find('\0') != std::string_view::npos) {
    out.error = located(source, 0, "not a text file (it contains NUL bytes)");
    return out;
  }
  std::string safe_text;
  int hazard_line = 0;
  if (const std::string hazard = tomlpp_safe_text(text, &safe_text, &hazard_line);
      !hazard.empty()) {
    out.error = located(source, hazard_line, "malformed TOML: " + hazard);
    return out;
  }
  toml::table root;
  try {
    root = toml::parse(safe_text, source);
  } catch (const toml::parse_error& e) {
    std::string what(e.description());
    std::replace(what.begin(), what.end(), '\n', ' ');
    out.error = located(source, static_cast<int>(e.source().begin.line),
                        "malformed TOML: " + printable(what, 200));
    return out;
  }
  SceneDef s;
  s.has_gravity = s.has_ground = s.has_ceiling = false;
  {  // name defaults to the file's stem
    std::string stem = source.substr(source.find_last_of('/') + 1);
    s.name = stem.substr(0, stem.rfind('.'));
  }
  std::map<std::string, int> lines;  // "section.key" -> line, for validation errors
  MaterialInput material;
  int material_line = 0;
  for (auto&& [key, node] : root) {
    const std::string k(key.str());
    const int line = static_cast<int>(node.source().begin.line);
    if (k == "name") {
      if (auto r = read_string(node, s.name); !r.empty())
        return {std::nullopt, located(source, line, "name: " + r)};
      if (has_control_characters(s.name))
        return {std::nullopt, located(source, line, "name: must not contain control characters")};
      continue;
    }
    if (!is_section(k)) {
      const bool looks_like_key = !node.is_table();
      std::string hint = did_you_mean(k, {std::begin(kSections), std::end(kSections)});
      return {
          std::nullopt,
          located(source, line,
                  printable(k) + ": " +
                      (looks_like_key
                           ? "unknown top-level key (only \"name\" and sections are allowed)" + hint
                           : unknown_section_error(k)))};
    }
    const toml::table* table = node.as_table();
    if (!table)
      return {
          std::nullopt,
          located(source, line, k + ": expected a [" + k + "] section, got " + type_name(node))};
    if (bool* flag = term_flag(s, k)) *flag = true;
    // Two passes: `enabled` last, so `enabled = false` wins over the other keys of its
    // section (which switch the term on, as they do in --set) whatever their order.
    for (int pass = 0; pass < 2; ++pass) {
      for (auto&& [sub, value] : *table) {
        const std::string sk(sub.str());
        if ((sk == "enabled") != (pass == 1)) continue;
        const std::string full = k + "." + printable(sk);
        const int vline = static_cast<int>(value.source().begin.line);
        const KeySpec* spec = find_key(k, sk);
        if (!spec)
          return {std::nullopt,
                  located(source, vline, full + ": unknown key" + did_you_mean(sk, keys_of(k)))};
        if (auto r = apply_key(s, k, *spec, value, &material); !r.empty())
          return {std::nullopt, located(source, vline, full + ": " + r)};
        lines[full] = vline;
        if (k == "material") material_line = std::max(material_line, vline);
      }
    }
  }
  if (auto r = set_material(s, material); !r.empty()) {
    const std::string key = r.substr(0, r.find(':'));
    return {std::nullopt, located(source, lines.count(key) ? lines[key] : material_line, r)};
  }
  if (auto r = validate_scene(s); !r.empty()) {
    const std::string key = r.substr(0, r.find(':'));
    return {std::nullopt, located(source, lines.count(key) ? lines[key] : 0, r)};
  }
  out.scene = std::move(s);
  return out;
}

SceneLoad load_scene(const std::string& name_or_path) {
  if (auto builtin = find_builtin_scene(name_or_path)) return {builtin, ""};
  const std::string where = printable(name_or_path, 200);
  auto error = [&](const std::string& what) {
    return SceneLoad{std::nullopt, where + ": " + what};
  };
  struct stat st {};
  if (::stat(name_or_path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) {
      std::string names;
      for (const auto& e : builtin_scenes())
        names += std::string(names.empty() ? "" : ", ") + e.name;
      return error("no such file, and not a built-in scene (" + names + ")");
    }
    return error(std::string("cannot open: ") + std::strerror(err));
  }
  if (S_ISDIR(st.st_mode)) return error("is a directory, not a scene file");
  if (!S_ISREG(st.st_mode)) return error("not a regular file");
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxSceneFileBytes)
    return error("too large for a scene file (" + std::to_string(st.st_size) + " bytes, at most " +
                 std::to_string(kMaxSceneFileBytes) + ")");
  std::ifstream in(name_or_path, std::ios::binary);
  if (!in) return error(std::string("cannot open: ") + std::strerror(errno));
  std::string text;
  // Read at most one byte past the limit: the file may have grown since stat().
  text.resize(kMaxSceneFileBytes + 1);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) return error("could not read the file");
  text.resize(static_cast<size_t>(in.gcount()));
  if (text.size() > kMaxSceneFileBytes) return error("too large for a scene file");
  return parse_scene_toml(text, name_or_path);
}

std::string apply_override(SceneDef& s, std::string_view assignment) {
  const std::string where = "--set " + printable(assignment);
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos) return where + ": expected section.key=value";
  const std::string lhs(assignment.substr(0, eq));
  std::string rhs(assignment.substr(eq + 1));
  const size_t dot = lhs.find('.');
  if (dot == std::string::npos) return where + ": expected section.key=value";
  const std::string section = lhs.substr(0, dot), key = lhs.substr(dot + 1);
  if (!is_section(section))
    return where + ": " + printable(section) + ": " + unknown_section_error(section);
  const KeySpec* spec = find_key(section, key);
  if (!spec)
    return where + ": " + printable(lhs) + ": unknown key" + did_you_mean(key, keys_of(section));
  // The value in TOML syntax; failing that, a bare word stands for a string
  // (--set material.model=linear).
  auto parse_value = [](const std::string& text, toml::table& out) {
    int line = 0;
    std::string safe_text;
    if (!tomlpp_safe_text(text, &safe_text, &line).empty()) return false;
    try {
      out = toml::parse(safe_text);
      return true;
    } catch (const toml::parse_error&) {
      return false;
    }
  };
  toml::table parsed;
  if (!parse_value("v = " + rhs, parsed)) {
    std::string escaped;
    for (char c : rhs) {
      if (c == '"' || c == '\\') escaped += '\\';
      escaped += c;
    }
    if (!parse_value("v = \"" + escaped + "\"", parsed))
      return where + ": " + lhs + ": cannot parse the value";
  }
  // "v = 1\n[mesh]\nside = 2" parses, but is not one value.
  if (parsed.size() != 1 || !parsed.get("v"))
    return where + ": " + lhs + ": expected a single value";
  SceneDef candidate = s;
  MaterialInput material;
  if (auto r = apply_key(candidate, section, *spec, *parsed.get("v"), &material); !r.empty())
    return where + ": " + lhs + ": " + r;
  if (auto r = set_material(candidate, material); !r.empty()) return where + ": " + r;
  if (auto r = validate_scene(candidate); !r.empty()) return where + ": " + r;
  s = std::move(candidate);
  return "";
}

std::vector<std::string> scene_keys() {
  std::vector<std::string> out;
  for (const auto& k : kKeys) out.push_back(std::string(k.section) + "." + k.key);
  return out;
}

namespace {
// A TOML basic string: quotes, backslashes and control characters escaped.
std::string toml_string(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", u);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}
}  // namespace

std::string scene_to_toml(const SceneDef& s) {
  // Every key is written, and a switched-off term keeps its values under `enabled = false`,
  // so that parsing the text gives back exactly this scene.
  std::ostringstream o;
  o.precision(17);
  auto vec = [](const Vec2& v) {
    std::ostringstream t;
    t.precision(17);
    t << "[" << v.x() << ", " << v.y() << "]";
    return t.str();
  };
  auto enabled = [](bool on) { return on ? "" : "enabled = false\n"; };
  o << "name = " << toml_string(s.name) << "\n\n";
  o << "[mesh]\nside = " << s.side << "\nn_seg = " << s.n_seg << "\ndensity = " << s.density
    << "\nmass = \"" << (s.mass == MassMode::Uniform ? "uniform" : "lumped")
    << "\"\njitter = " << s.jitter << "\nseed = " << s.seed << "\n";
  o << "\n[material]\nmodel = \"" << model_name(s.model) << "\"\nmu = " << s.lame.mu
    << "\nlambda = " << s.lame.lambda << "\n";
  o << "\n[time]\nh = " << s.h << "\ntol = " << s.tol << "\nmax_newton = " << s.max_newton << "\n";
  o << "\n[solver]\nprojection = \"" << projection_name(s.projection)
    << "\"\ninversion_filter = " << (s.inversion_filter ? "true" : "false") << "\nintegrator = \""
    << integrator_name(s.integrator) << "\"\nlinear_solver = \""
    << linear_solver_name(s.linear_solver)
    << "\"\nstep_expansion = " << (s.step_expansion ? "true" : "false")
    << "\nfriction_crossing_stop = " << (s.friction_crossing_stop ? "true" : "false") << "\n";
  o << "\n[initial]\nvelocity = " << vec(s.initial_velocity) << "\n";
  o << "\n[gravity]\n" << enabled(s.has_gravity) << "g = " << vec(s.gravity) << "\n";
  o << "\n[ground]\n"
    << enabled(s.has_ground) << "y = " << s.ground_y << "\nfriction = " << s.friction << "\n";
  o << "\n[ceiling]\n"
    << enabled(s.has_ceiling) << "y = " << s.ceiling_y << "\nvelocity = " << s.ceiling_velocity
    << "\nstop = " << s.ceiling_stop << "\n";
  o << "\n[barrier]\ndhat = " << s.dhat << "\nkappa = " << s.kappa << "\n";
  return o.str();
}

}  // namespace invfree

#include "scene_io/key_table.h"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "scene_io/error_text.h"
#include "scene_io/scene_keys.h"

namespace invfree::scene_io {

namespace {
constexpr EnumName<toml::node_type> kTomlTypeNames[] = {
    {toml::node_type::table, "a table"},           {toml::node_type::array, "an array"},
    {toml::node_type::string, "a string"},         {toml::node_type::integer, "an integer"},
    {toml::node_type::floating_point, "a number"}, {toml::node_type::boolean, "a boolean"}};
}  // namespace

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

std::string toml_type_name(const toml::node& n) {
  return enum_name(kTomlTypeNames, n.type(), "a date/time");
}

std::string read_number(const toml::node& n, double& out) {
  if (auto v = n.value<double>(); v && (n.is_integer() || n.is_floating_point())) {
    out = *v;
    if (!std::isfinite(out)) return "must be a finite number";
    return "";
  }
  return "expected a number, got " + toml_type_name(n);
}

std::string bounds_problem(std::string_view key, double v) {
  const ValueBounds* b = find_value_bounds(key);
  return b && !b->contains(v) ? b->requirement() : "";
}

std::string unreadable_number(std::string_view text) {
  size_t k = 0;
  while (k < text.size()) {
    const size_t end = text.find_first_of(" \t,[]", k);
    const std::string token(text.substr(k, end == std::string_view::npos ? text.npos : end - k));
    k = end == std::string_view::npos ? text.size() : end + 1;
    if (token.empty() || token.find_first_of("0123456789") == std::string::npos) continue;
    std::string digits = token;
    digits.erase(std::remove(digits.begin(), digits.end(), '_'), digits.end());  // TOML's 1_000
    errno = 0;
    char* stop = nullptr;
    const double v = std::strtod(digits.c_str(), &stop);
    if (stop == digits.c_str() + digits.size() && errno == ERANGE && std::isinf(v))
      return printable(token, 40) +
             " is beyond a double's range (about 1.8e308): must be a finite number";
  }
  return "";
}

// ---- typed readers: return "" or a reason -------------------------------------------

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
  return "expected an integer, got " + toml_type_name(n);
}

namespace {

std::string read_bool(const toml::node& n, bool& out) {
  if (!n.is_boolean()) return "expected true or false, got " + toml_type_name(n);
  out = n.as_boolean()->get();
  return "";
}

}  // namespace

std::string read_vec2(const toml::node& n, Vec2& out) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) return "expected an array of two numbers, e.g. [0.0, -9.81]";
  for (int k = 0; k < 2; ++k)
    if (auto r = read_number(*a->get(k), out[k]); !r.empty())
      return "element " + std::to_string(k) + ": " + r;
  return "";
}

std::string read_points(const toml::node& n, Loop& out) {
  const toml::array* a = n.as_array();
  if (!a) return "expected an array of points, e.g. [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]";
  out.clear();
  out.reserve(a->size());
  for (size_t k = 0; k < a->size(); ++k) {
    Vec2 p = Vec2::Zero();
    if (auto r = read_vec2(*a->get(k), p); !r.empty())
      return "point " + std::to_string(k) + ": " +
             (r.rfind("expected an array", 0) == 0 ? std::string("expected [x, y]") : r);
    out.push_back(p);
  }
  return "";
}

std::string read_loops(const toml::node& n, std::vector<Loop>& out) {
  const toml::array* a = n.as_array();
  if (!a) return "expected an array of polygons, e.g. [[[0.1, 0.1], [0.2, 0.1], [0.1, 0.2]]]";
  out.assign(a->size(), Loop{});
  for (size_t k = 0; k < a->size(); ++k)
    if (auto r = read_points(*a->get(k), out[k]); !r.empty())
      return "polygon " + std::to_string(k) + ": " + r;
  return "";
}

namespace {

// [[i, j], ...]: node indices, each an integer >= 0 that fits an int (find_scene_problem
// checks them against the mesh).
std::string read_pairs(const toml::node& n, IndexPairs& out) {
  const toml::array* a = n.as_array();
  if (!a) return "expected an array of node pairs, e.g. [[0, 1], [1, 2]]";
  out.clear();
  out.reserve(a->size());
  for (size_t k = 0; k < a->size(); ++k) {
    const toml::array* pair = a->get(k)->as_array();
    if (!pair || pair->size() != 2) return "pair " + std::to_string(k) + ": expected [i, j]";
    std::array<int, 2> p{};
    for (int e = 0; e < 2; ++e) {
      long long v = 0;
      if (auto r = read_int(*pair->get(e), v); !r.empty())
        return "pair " + std::to_string(k) + ": element " + std::to_string(e) + ": " + r;
      if (v < 0 || v > std::numeric_limits<int>::max())
        return "pair " + std::to_string(k) + ": element " + std::to_string(e) +
               ": must be a node index >= 0";
      p[e] = static_cast<int>(v);
    }
    out.push_back(p);
  }
  return "";
}

std::string choice_list(const std::vector<std::string>& choices) {
  std::string out;
  for (const auto& c : choices) out += (out.empty() ? "\"" : ", \"") + c + "\"";
  return out;
}

// The TOML value as a value of the field's type; "" or the reason.
std::string read_value(const SceneField& f, const toml::node& n, FieldValue& out) {
  std::string r;
  switch (f.type) {
    case FieldType::Number: {
      double v = 0.0;
      r = read_number(n, v);
      out = v;
      break;
    }
    case FieldType::Integer: {
      long long v = 0;
      r = read_int(n, v);
      out = v;
      break;
    }
    case FieldType::Boolean: {
      bool v = false;
      r = read_bool(n, v);
      out = v;
      break;
    }
    case FieldType::Vector: {
      Vec2 v = Vec2::Zero();
      r = read_vec2(n, v);
      out = v;
      break;
    }
    case FieldType::Text: {
      if (!n.is_string()) return "expected a string, got " + toml_type_name(n);
      out = n.as_string()->get();
      break;
    }
    case FieldType::Points: {
      Loop v;
      r = read_points(n, v);
      out = std::move(v);
      break;
    }
    case FieldType::Loops: {
      std::vector<Loop> v;
      r = read_loops(n, v);
      out = std::move(v);
      break;
    }
    case FieldType::Pairs: {
      IndexPairs v;
      r = read_pairs(n, v);
      out = std::move(v);
      break;
    }
    case FieldType::Choice: {
      if (!n.is_string()) return "expected a string, got " + toml_type_name(n);
      const std::string text = n.as_string()->get();
      const std::vector<std::string> choices = f.choices();
      if (std::find(choices.begin(), choices.end(), text) == choices.end())
        // invfree:: so that libc++'s std::quoted (found by ADL) is not taken
        return "unknown value " + invfree::quoted(text) + " (expected one of " +
               choice_list(choices) + ")";
      out = text;
      break;
    }
  }
  return r;
}

}  // namespace

std::string read_field(const SceneField& f, SceneDef& s, MaterialInput& material,
                       const toml::node& n) {
  FieldValue v;
  if (auto r = read_value(f, n, v); !r.empty()) return r;
  return assign_field(f, s, material, v);
}

std::string write_field(const SceneField& f, const SceneDef& s) {
  return value_text(f.get(s));
}

std::string value_text(const FieldValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return toml_number(*d);
  if (const auto* i = std::get_if<long long>(&v)) return std::to_string(*i);
  if (const auto* u = std::get_if<unsigned long long>(&v)) return std::to_string(*u);
  if (const auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (const auto* c = std::get_if<std::string>(&v)) return toml_string(*c);
  if (const auto* loop = std::get_if<Loop>(&v)) {
    std::string out(1, '[');
    for (size_t k = 0; k < loop->size(); ++k) {
      if (k) out += ", ";
      out += value_text(FieldValue((*loop)[k]));
    }
    out += ']';
    return out;
  }
  if (const auto* loops = std::get_if<std::vector<Loop>>(&v)) {
    std::string out(1, '[');
    for (size_t k = 0; k < loops->size(); ++k) {
      if (k) out += ", ";
      out += value_text(FieldValue((*loops)[k]));
    }
    out += ']';
    return out;
  }
  if (const auto* pairs = std::get_if<IndexPairs>(&v)) {
    std::string out(1, '[');
    for (size_t k = 0; k < pairs->size(); ++k)
      out += (k ? ", [" : "[") + std::to_string((*pairs)[k][0]) + ", " +
             std::to_string((*pairs)[k][1]) + "]";
    out += ']';
    return out;
  }
  const Vec2& u = std::get<Vec2>(v);
  std::string out(1, '[');
  out += toml_number(u.x());
  out += ", ";
  out += toml_number(u.y());
  out += ']';
  return out;
}

std::vector<std::string> keys_of(std::string_view section) {
  std::vector<std::string> out;
  for (const auto& f : scene_fields())
    if (section == f.section) out.emplace_back(f.key);
  return out;
}

std::vector<std::string> section_names() {
  std::vector<std::string> out;
  for (const auto& s : scene_sections()) out.emplace_back(s.name);
  return out;
}

std::string toml_number(double v) {
  char buf[64];
#ifdef __EMSCRIPTEN__
  // emscripten 3.1.6's libc++ has no floating-point std::to_chars: the shortest %g that
  // reads back to v (the web page; the same number, possibly spelt otherwise).
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::string t(buf);
#else
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  std::string t(buf, ec == std::errc() ? end : buf);
#endif
  const size_t e = t.find('e');
  if (e == std::string::npos) {
    if (t.find_first_of(".ni") == std::string::npos) t += ".0";  // "100" would be an integer
    return t;
  }
  // "1e+05" -> "1e5", "2.5e-07" -> "2.5e-7"
  std::string exponent = t.substr(e + 1);
  const bool negative = exponent[0] == '-';
  if (exponent[0] == '+' || exponent[0] == '-') exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return t.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

}  // namespace invfree::scene_io

namespace invfree {

std::vector<std::string> scene_keys() {
  std::vector<std::string> out;
  for (const auto& f : scene_fields()) out.push_back(f.name());
  return out;
}

std::vector<SceneKeyInfo> scene_key_info() {
  const SceneDef defaults;
  std::vector<SceneKeyInfo> out;
  for (const auto& f : scene_fields()) {
    SceneKeyInfo info{f.section,
                      f.key,
                      field_type_name(f.type),
                      f.unit,
                      "",
                      f.choices(),
                      scene_io::write_field(f, defaults),
                      f.doc};
    if (const ValueBounds* b = find_value_bounds(f.name())) info.range = b->range();
    out.push_back(std::move(info));
  }
  return out;
}

std::vector<SceneSectionInfo> scene_section_info() {
  std::vector<SceneSectionInfo> out;
  for (const auto& s : scene_sections()) out.push_back({s.name, s.term != nullptr, s.doc});
  return out;
}

}  // namespace invfree

#include "scene_io/body_tables.h"

#include <algorithm>
#include <cmath>

#include "scene_io/did_you_mean.h"
#include "scene_io/error_text.h"
#include "scene_io/scene_keys.h"

namespace invfree::scene_io {

namespace {

// A number within the range of the [mesh] or [material] key it stands for.
std::string number_in(const std::string& bounds_key, const toml::node& n, double& out) {
  if (auto r = read_number(n, out); !r.empty()) return r;
  return bounds_problem(bounds_key, out);
}

std::string vec2_in(const toml::node& n, Vec2& out) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) return "expected an array of two numbers, e.g. [0.0, -0.5]";
  for (int k = 0; k < 2; ++k) {
    const toml::node& e = *a->get(k);
    const auto v = e.value<double>();
    if (!v || !(e.is_integer() || e.is_floating_point()) || !std::isfinite(*v))
      return "element " + std::to_string(k) + ": expected a finite number";
    out[k] = *v;
  }
  return "";
}

// One key of a [[body]] table into `in`; "" or the reason. A number is within the range of
// the [mesh] or [material] key it stands for; n_seg is read as every integer key (read_int).
std::string read_body_key(const BodyField& f, const toml::node& n, BodyInput& in) {
  FieldValue value;
  if (f.type == FieldType::Number) {
    double v = 0.0;
    if (auto r = number_in(f.stands_for, n, v); !r.empty()) return r;
    value = v;
  } else if (f.type == FieldType::Integer) {
    long long i = 0;
    if (auto r = read_int(n, i); !r.empty()) return r;
    if (auto r = bounds_problem(f.stands_for, static_cast<double>(i)); !r.empty()) return r;
    value = i;
  } else if (f.type == FieldType::Choice) {
    if (!n.is_string()) return "expected a string, got " + toml_type_name(n);
    const std::string text = n.as_string()->get();
    const std::vector<std::string> choices = f.choices();
    if (std::find(choices.begin(), choices.end(), text) == choices.end()) {
      std::string list;
      for (const auto& c : choices) list += (list.empty() ? "\"" : ", \"") + c + "\"";
      return "unknown value " + invfree::quoted(text) + " (expected one of " + list + ")";
    }
    value = text;
  } else if (f.type == FieldType::Text) {
    if (!n.is_string()) return "expected a string, got " + toml_type_name(n);
    value = n.as_string()->get();
  } else if (f.type == FieldType::Points) {
    Loop points;
    if (auto r = read_points(n, points); !r.empty()) return r;
    value = std::move(points);
  } else if (f.type == FieldType::Loops) {
    std::vector<Loop> loops;
    if (auto r = read_loops(n, loops); !r.empty()) return r;
    value = std::move(loops);
  } else {
    Vec2 u = Vec2::Zero();
    if (auto r = vec2_in(n, u); !r.empty()) return r;
    value = u;
  }
  if (f.input)
    in.material.*(f.input) = std::get<double>(value);
  else
    f.set(in.body, value);
  return "";
}

BodyError located(int line, std::string what) {
  return {line, std::move(what)};
}

}  // namespace

std::vector<std::string> body_keys() {
  std::vector<std::string> out;
  for (const auto& f : body_fields()) out.emplace_back(f.key);
  return out;
}

BodyError read_body_tables(const toml::node& node, std::vector<BodyInput>& out) {
  const int line = static_cast<int>(node.source().begin.line);
  const toml::array* tables = node.as_array();
  if (!tables || !tables->is_array_of_tables())
    return located(
        line, "body: expected [[body]] tables (an array of tables), got " + toml_type_name(node));
  if (tables->size() > static_cast<size_t>(kMaxBodies))
    return located(line, "body: at most " + std::to_string(kMaxBodies) + " [[body]] tables, got " +
                             std::to_string(tables->size()));
  const std::vector<std::string> keys = body_keys();
  for (size_t k = 0; k < tables->size(); ++k) {
    const toml::table& t = *tables->get(k)->as_table();
    BodyInput in;
    in.line = static_cast<int>(t.source().begin.line);
    const std::string which = " (in [[body]] " + std::to_string(k + 1) + ")";
    for (auto&& [key, value] : t) {
      const std::string name(key.str());
      const int vline = static_cast<int>(value.source().begin.line);
      bool known = false;
      for (const auto& s : keys) known = known || s == name;
      if (!known)
        return located(vline, "body." + printable(name) + ": unknown key" +
                                  did_you_mean(name, keys) +
                                  " (keys of [[body]]: " + join_words(keys) + ")");
      if (auto r = read_body_key(*find_body_field(name), value, in); !r.empty())
        return located(vline, "body." + name + ": " + r + which);
      in.key_lines.emplace_back(name, vline);
    }
    out.push_back(std::move(in));
  }
  return {};
}

std::string apply_body_materials(SceneDef& scene, std::span<const BodyInput> in, int* line) {
  scene.bodies.clear();
  for (size_t k = 0; k < in.size(); ++k) {
    BodyDef body = in[k].body;
    const MaterialInput& m = in[k].material;
    if (m.E || m.nu || m.mu || m.lambda) {
      SceneDef own = scene;  // the scene's material, changed by the body's keys
      if (auto r = apply_material(own, m); !r.empty()) {
        const std::string key = r.substr(r.find('.') + 1, r.find(':') - r.find('.') - 1);
        *line = in[k].line;
        for (const auto& [name, l] : in[k].key_lines)
          if (name == key) *line = l;
        return "body." + r.substr(r.find('.') + 1) + " (in [[body]] " + std::to_string(k + 1) + ")";
      }
      body.lame = own.lame;
    }
    scene.bodies.push_back(body);
  }
  return "";
}

std::string body_tables_to_toml(const SceneDef& scene) {
  std::string out;
  for (const BodyDef& b : scene.bodies) {
    out += "\n[[body]]\n";
    for (const auto& f : body_fields())
      if (const auto v = f.get ? f.get(b) : std::nullopt)
        out += std::string(f.key) + " = " + value_text(*v) + "\n";
  }
  return out;
}

}  // namespace invfree::scene_io

namespace invfree {

std::vector<SceneKeyInfo> body_key_info() {
  const BodyDef defaults;
  std::vector<SceneKeyInfo> out;
  for (const auto& f : body_fields()) {
    const auto v = f.get ? f.get(defaults) : std::nullopt;
    SceneKeyInfo info{"body", f.key, field_type_name(f.type),           f.unit,
                      "",     {},    v ? scene_io::value_text(*v) : "", f.doc};
    if (const ValueBounds* b = f.stands_for ? find_value_bounds(f.stands_for) : nullptr)
      info.range = b->range();
    out.push_back(std::move(info));
  }
  return out;
}

}  // namespace invfree

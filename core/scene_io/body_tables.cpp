#include "scene_io/body_tables.h"

#include <cmath>

#include "scene_io/did_you_mean.h"
#include "scene_io/error_text.h"
#include "scene_io/scene_keys.h"

namespace invfree::scene_io {

namespace {

constexpr BodyKeyDoc kBodyKeys[] = {
    {"side", "number", "m", "edge length of this body's square (default: mesh.side)"},
    {"n_seg", "integer", "", "segments per side (default: mesh.n_seg)"},
    {"offset", "[x, y]", "m", "the square's centre at rest"},
    {"velocity", "[x, y]", "m/s", "its velocity at t = 0 (default: initial.velocity)"},
    {"E", "number", "Pa", "its own Young's modulus (default: [material])"},
    {"nu", "number", "", "its own Poisson's ratio"},
    {"mu", "number", "Pa", "its own Lame mu, instead of E and nu"},
    {"lambda", "number", "Pa", "its own Lame lambda, instead of E and nu"},
};

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

// One key of a [[body]] table into `in`; "" or the reason.
std::string read_body_key(const std::string& key, const toml::node& n, BodyInput& in) {
  double v = 0.0;
  if (key == "side") {
    if (auto r = number_in("mesh.side", n, v); !r.empty()) return r;
    in.body.side = v;
  } else if (key == "n_seg") {
    if (!n.is_integer()) return "expected an integer, got " + toml_type_name(n);
    const long long i = n.as_integer()->get();
    if (auto r = bounds_problem("mesh.n_seg", static_cast<double>(i)); !r.empty()) return r;
    in.body.n_seg = static_cast<int>(i);
  } else if (key == "offset") {
    return vec2_in(n, in.body.offset);
  } else if (key == "velocity") {
    Vec2 u;
    if (auto r = vec2_in(n, u); !r.empty()) return r;
    in.body.velocity = u;
  } else {  // E, nu, mu, lambda
    if (auto r = number_in("material." + key, n, v); !r.empty()) return r;
    (key == "E"    ? in.material.E
     : key == "nu" ? in.material.nu
     : key == "mu" ? in.material.mu
                   : in.material.lambda) = v;
  }
  return "";
}

BodyError located(int line, std::string what) {
  return {line, std::move(what)};
}

}  // namespace

std::span<const BodyKeyDoc> body_key_docs() {
  return kBodyKeys;
}

std::vector<std::string> body_keys() {
  std::vector<std::string> out;
  for (const auto& k : kBodyKeys) out.emplace_back(k.key);
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
      if (auto r = read_body_key(name, value, in); !r.empty())
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
    if (b.side) out += "side = " + toml_number(*b.side) + "\n";
    if (b.n_seg) out += "n_seg = " + std::to_string(*b.n_seg) + "\n";
    out += "offset = [" + toml_number(b.offset.x()) + ", " + toml_number(b.offset.y()) + "]\n";
    if (b.velocity)
      out += "velocity = [" + toml_number(b.velocity->x()) + ", " + toml_number(b.velocity->y()) +
             "]\n";
    if (b.lame)
      out += "mu = " + toml_number(b.lame->mu) + "\nlambda = " + toml_number(b.lame->lambda) + "\n";
  }
  return out;
}

}  // namespace invfree::scene_io

namespace invfree {

std::vector<SceneKeyInfo> body_key_info() {
  std::vector<SceneKeyInfo> out;
  for (const auto& k : scene_io::body_key_docs()) {
    const std::string key = k.key;
    SceneKeyInfo info{"body", k.key, k.type, k.unit, "", {}, key == "offset" ? "[0.0, 0.0]" : "",
                      k.doc};
    const std::string stands_for = key == "side" || key == "n_seg"        ? "mesh." + key
                                   : key == "offset" || key == "velocity" ? ""
                                                                          : "material." + key;
    if (const ValueBounds* b = stands_for.empty() ? nullptr : find_value_bounds(stands_for))
      info.range = b->range();
    out.push_back(std::move(info));
  }
  return out;
}

}  // namespace invfree

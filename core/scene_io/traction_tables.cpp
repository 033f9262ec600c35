#include "scene_io/traction_tables.h"

#include <cmath>

#include "scene_io/did_you_mean.h"
#include "scene_io/error_text.h"
#include "scene_io/key_table.h"

namespace invfree::scene_io {

namespace {

struct TractionKey {
  const char* key;
  const char* type;
  const char* unit;
  const char* doc;
  bool vector;
  Vec2 TractionDef::*vec = nullptr;
  double TractionDef::*number = nullptr;
};

constexpr TractionKey kKeys[] = {
    {"box_min", "[x, y]", "m",
     "the loaded boundary edges: both nodes (at rest) in [box_min, box_max]", true,
     &TractionDef::box_min},
    {"box_max", "[x, y]", "m", "the box's upper corner", true, &TractionDef::box_max},
    {"force", "[x, y]", "N/m",
     "dead load: the total force per unit thickness, spread over the edges by length", true,
     &TractionDef::force},
    {"pressure", "number", "Pa",
     "follower pressure on the deformed edges, into the body (> 0); whole boundary loops only",
     false, nullptr, &TractionDef::pressure},
};

TractionError read_table(const toml::table& t, const std::string& which, TractionDef& out) {
  const std::vector<std::string> keys = traction_keys();
  for (auto&& [key, value] : t) {
    const std::string name(key.str());
    const int line = static_cast<int>(value.source().begin.line);
    const TractionKey* spec = nullptr;
    for (const auto& k : kKeys)
      if (name == k.key) spec = &k;
    if (!spec)
      return {line, "traction." + printable(name) + ": unknown key" + did_you_mean(name, keys) +
                        " (keys of [traction]: " + join_words(keys) + ")" + which};
    std::string r;
    if (spec->vector) {
      r = read_vec2(value, out.*(spec->vec));
    } else {
      double v = 0.0;
      r = read_number(value, v);
      if (r.empty()) out.*(spec->number) = v;
    }
    if (!r.empty()) return {line, "traction." + name + ": " + r + which};
  }
  return {};
}

}  // namespace

std::vector<std::string> traction_keys() {
  std::vector<std::string> out;
  for (const auto& k : kKeys) out.emplace_back(k.key);
  return out;
}

TractionError read_traction_tables(const toml::node& node, std::vector<TractionDef>& out) {
  const int line = static_cast<int>(node.source().begin.line);
  out.clear();
  if (const toml::table* t = node.as_table()) {
    TractionDef d;
    if (auto e = read_table(*t, "", d); !e.message.empty()) return e;
    out.push_back(d);
    return {};
  }
  const toml::array* tables = node.as_array();
  if (!tables || !tables->is_array_of_tables())
    return {line, "traction: expected a [traction] table or [[traction]] tables, got " +
                      toml_type_name(node)};
  if (tables->size() > static_cast<size_t>(kMaxTractions))
    return {line, "traction: at most " + std::to_string(kMaxTractions) +
                      " [[traction]] tables, got " + std::to_string(tables->size())};
  for (size_t k = 0; k < tables->size(); ++k) {
    TractionDef d;
    const std::string which =
        tables->size() > 1 ? " (in [[traction]] " + std::to_string(k + 1) + ")" : "";
    if (auto e = read_table(*tables->get(k)->as_table(), which, d); !e.message.empty()) return e;
    out.push_back(d);
  }
  return {};
}

std::string traction_tables_to_toml(const SceneDef& scene) {
  std::string out;
  for (const TractionDef& t : scene.tractions) {
    out += "\n[[traction]]\n";
    for (const auto& k : kKeys)
      out +=
          std::string(k.key) + " = " +
          (k.vector ? value_text(FieldValue(t.*(k.vec))) : value_text(FieldValue(t.*(k.number)))) +
          "\n";
  }
  return out;
}

}  // namespace invfree::scene_io

namespace invfree {

std::vector<SceneKeyInfo> traction_key_info() {
  const TractionDef defaults;
  std::vector<SceneKeyInfo> out;
  for (const auto& k : scene_io::kKeys) {
    const std::string def = k.vector ? scene_io::value_text(FieldValue(defaults.*(k.vec)))
                                     : scene_io::value_text(FieldValue(defaults.*(k.number)));
    out.push_back({"traction", k.key, k.type, k.unit, "", {}, def, k.doc});
  }
  return out;
}

}  // namespace invfree

#include "scene_io/scene_file.h"

#include <sys/stat.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <vector>

#include "scene_io/body_tables.h"
#include "scene_io/builtin_scenes.h"
#include "scene_io/did_you_mean.h"
#include "scene_io/error_text.h"
#include "scene_io/key_table.h"
#include "scene_io/shape_files.h"
#include "scene_io/toml_guard.h"
#include "scene_io/traction_tables.h"

namespace invfree {

namespace {

// Scene files larger than this are certainly not scenes (the built-in ones are < 1 kB);
// refusing them keeps `--scene /dev/zero` or a stray video from eating memory.
constexpr std::uintmax_t kMaxSceneFileBytes = 1 << 20;

std::string unknown_section_error(std::string_view section) {
  const std::vector<std::string> names = scene_io::section_names();
  return "unknown section" + did_you_mean(section, names) + " (sections: " + join_words(names) +
         ")";
}

// "unknown key", the nearest key of the section and the list of its keys.
std::string unknown_key_error(const std::string& section, std::string_view key) {
  const std::vector<std::string> keys = scene_io::keys_of(section);
  return "unknown key" + did_you_mean(key, keys) + " (keys of [" + section +
         "]: " + join_words(keys) + ")";
}

// Reads one key (known to exist) into the scene; a key of a term's section other than
// `enabled` switches the term on, as the section's presence does. Returns "" or a reason.
std::string apply_key(SceneDef& s, const SceneField& spec, const toml::node& value,
                      MaterialInput& material) {
  const SceneSection* section = find_scene_section(spec.section);
  if (section && section->term && std::string_view(spec.key) != "enabled")
    s.*(section->term) = true;
  return scene_io::read_field(spec, s, material, value);
}

// The message for a problem validation found, naming a key the user wrote: the problem's
// own key when written, otherwise the first written of the keys its check read (the
// problem's key is then named in the reason when the reason is about it: "must be ...").
struct Blame {
  std::string key;
  std::string message;
};
// Self-contact asked for where it cannot run (self_contact_can_run): why, or none.
std::optional<SceneProblem> self_contact_refusal(const SceneDef& s) {
  if (!s.has_self_contact || self_contact_can_run(s)) return std::nullopt;
  const std::string key = "self_contact.enabled";
  if (s.has_mass_spring)
    return SceneProblem{
        key, "is not available with [mass_spring] (springs need a fixed Hessian pattern)", {}};
  return SceneProblem{
      key, "is not available with [fixed] (fixed nodes need a fixed Hessian pattern)", {}};
}

template <class Written>
Blame blame(const SceneProblem& p, Written written) {
  if (!written(p.key))
    for (const auto& cause : p.causes)
      if (written(cause)) {
        const bool about_key = p.reason.rfind("must", 0) == 0;
        return {cause, cause + ": " + (about_key ? p.key + " " : "") + p.reason};
      }
  return {p.key, p.key + ": " + p.reason};
}

std::string located(const std::string& source, int line, const std::string& what) {
  const std::string where = printable(source, 200);
  return line > 0 ? where + ":" + std::to_string(line) + ": " + what : where + ": " + what;
}

// An error and the line it is on (0: none); `what` is empty when there is none.
struct LineError {
  int line = 0;
  std::string what;
};

// The text made safe for toml++ (toml_guard.h) and parsed into `root`.
LineError parse_toml(std::string_view text, const std::string& source, toml::table& root) {
  std::string safe_text;
  int hazard_line = 0;
  if (const std::string hazard = tomlpp_safe_text(text, &safe_text, &hazard_line); !hazard.empty())
    return {hazard_line, "malformed TOML: " + hazard};
  try {
    root = toml::parse(safe_text, source);
  } catch (const toml::parse_error& e) {
    std::string what(e.description());
    std::replace(what.begin(), what.end(), '\n', ' ');
    return {static_cast<int>(e.source().begin.line), "malformed TOML: " + printable(what, 200)};
  }
  return {};
}

// The keys of one [section] into the scene, each key's line into `lines`, each bad key's
// error into `errors` (every one: they do not depend on each other). Two passes:
// `enabled` last, so `enabled = false` wins over the other keys of its section (which
// switch the term on, as they do in --set) whatever their order.
void read_section(const std::string& k, const toml::table& table, SceneDef& s,
                  MaterialInput& material, std::map<std::string, int>& lines,
                  std::vector<LineError>& errors) {
  for (int pass = 0; pass < 2; ++pass) {
    for (auto&& [sub, value] : table) {
      const std::string sk(sub.str());
      if ((sk == "enabled") != (pass == 1)) continue;
      const std::string full = k + "." + printable(sk);
      const int vline = static_cast<int>(value.source().begin.line);
      const SceneField* spec = find_scene_field(k, sk);
      if (!spec) {
        errors.push_back({vline, full + ": " + unknown_key_error(k, sk)});
        continue;
      }
      if (auto r = apply_key(s, *spec, value, material); !r.empty()) {
        errors.push_back({vline, full + ": " + r});
        continue;
      }
      lines[full] = vline;
    }
  }
}

}  // namespace

SceneLoad parse_scene_toml(std::string_view text, const std::string& source) {
  auto fail = [&](int line, const std::string& what) {
    return SceneLoad{std::nullopt, located(source, line, what)};
  };
  if (text.find('\0') != std::string_view::npos)
    return fail(0, "not a text file (it contains NUL bytes)");
  toml::table root;
  if (const LineError e = parse_toml(text, source, root); !e.what.empty())
    return fail(e.line, e.what);
  SceneDef s;
  // Switched on by their sections; self-contact, on by default, is decided once every
  // other section is read: a file without [self_contact] gets self_contact_by_default, and
  // one that asks for it where it cannot run is refused.
  for (const auto& section : scene_sections())
    if (section.term && section.term != &SceneDef::has_self_contact) s.*(section.term) = false;
  int self_contact_line = 0;                      // of [self_contact]; 0: none
  {                                               // name defaults to the file's stem
    std::string stem = source.substr(source.find_last_of('/') + 1);
    s.name = stem.substr(0, stem.rfind('.'));
  }
  std::map<std::string, int> lines;  // "section.key" the user wrote -> its line
  MaterialInput material;
  std::vector<scene_io::BodyInput> bodies;
  // Every section's and key's own error (unknown names, wrong types, out of range): they do
  // not depend on each other, so a student sees all of them at once, in line order. The
  // checks of the scene as a whole below need every value read, so they come after.
  std::vector<LineError> errors;
  for (auto&& [key, node] : root) {
    const std::string k(key.str());
    const int line = static_cast<int>(node.source().begin.line);
    if (k == "body") {
      if (auto r = scene_io::read_body_tables(node, bodies); !r.message.empty())
        errors.push_back({r.line, r.message});
      continue;
    }
    if (k == "traction") {
      if (auto r = scene_io::read_traction_tables(node, s.tractions); !r.message.empty())
        errors.push_back({r.line, r.message});
      for (const auto& key : scene_io::traction_keys()) lines["traction." + key] = line;
      continue;
    }
    if (k == "name") {
      if (!node.is_string())
        errors.push_back(
            {line, "name: expected a string, got " + scene_io::toml_type_name(node)});
      else if (s.name = node.as_string()->get(); has_control_characters(s.name))
        errors.push_back({line, "name: must not contain control characters"});
      continue;
    }
    const SceneSection* section = find_scene_section(k);
    if (!section) {
      if (node.is_table())
        errors.push_back({line, printable(k) + ": " + unknown_section_error(k)});
      else
        errors.push_back({line, printable(k) +
                                    ": unknown top-level key (only \"name\" and sections are "
                                    "allowed)" +
                                    did_you_mean(k, scene_io::section_names())});
      continue;
    }
    const toml::table* table = node.as_table();
    if (!table) {
      errors.push_back(
          {line, k + ": expected a [" + k + "] section, got " + scene_io::toml_type_name(node)});
      continue;
    }
    if (section->term) s.*(section->term) = true;
    if (section->term == &SceneDef::has_self_contact) self_contact_line = line;
    read_section(k, *table, s, material, lines, errors);
  }
  if (!errors.empty()) {
    std::stable_sort(errors.begin(), errors.end(),
                     [](const LineError& a, const LineError& b) { return a.line < b.line; });
    std::string all;
    for (const LineError& e : errors) all += (all.empty() ? "" : "\n") + located(source, e.line, e.what);
    return SceneLoad{std::nullopt, all};
  }
  if (self_contact_line == 0) s.has_self_contact = self_contact_by_default(s);
  auto line_of = [&](const std::string& key) {
    const auto it = lines.find(key);
    return it == lines.end() ? 0 : it->second;
  };
  if (auto r = apply_material(s, material); !r.empty())
    return fail(line_of(r.substr(0, r.find(':'))), r);
  for (const auto& body : bodies)  // a problem with a body blames its key's last table
    for (const auto& [key, line] : body.key_lines) lines["body." + key] = line;
  int body_line = 0;
  if (auto r = scene_io::apply_body_materials(s, bodies, &body_line); !r.empty())
    return fail(body_line, r);
  if (auto r = scene_io::load_shape_files(s, source); !r.empty())
    return fail(line_of(r.substr(0, r.find(':'))), r);
  if (const auto problem = find_scene_problem(s)) {
    const Blame b = blame(*problem, [&](const std::string& key) { return lines.count(key) > 0; });
    return fail(line_of(b.key), b.message);
  }
  if (const auto problem = self_contact_refusal(s)) {
    const int line = line_of("self_contact.enabled");
    return fail(line > 0 ? line : self_contact_line, problem->key + ": " + problem->reason);
  }
  return {std::move(s), ""};
}

SceneLoad load_scene(const std::string& name_or_path) {
  for (const auto& e : builtin_scenes())
    if (e.name == name_or_path) return load_builtin_scene(e.name);
  const std::string where = printable(name_or_path, 200);
  auto error = [&](const std::string& what) {
    return SceneLoad{std::nullopt, where + ": " + what};
  };
  struct stat st {};
  if (::stat(name_or_path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) {
      std::vector<std::string> names;
      for (const auto& e : builtin_scenes()) names.emplace_back(e.name);
      return error("no such file, and not a built-in scene" + did_you_mean(name_or_path, names) +
                   " (" + builtin_scene_names() + ")");
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

namespace {

// One override read into `s` and `material` (the material keys wait for apply_material):
// its type and its own range checked, the scene as a whole not. Returns "" or the error;
// *lhs is "section.key".
std::string read_override(SceneDef& s, MaterialInput& material, std::string_view assignment,
                          std::string* lhs_out) {
  const std::string where = "--set " + printable(assignment);
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos) return where + ": expected section.key=value";
  const std::string lhs(assignment.substr(0, eq));
  std::string rhs(assignment.substr(eq + 1));
  const size_t dot = lhs.find('.');
  if (dot == std::string::npos) return where + ": expected section.key=value";
  const std::string section = lhs.substr(0, dot), key = lhs.substr(dot + 1);
  if (section == "body" || section == "traction")
    return where + ": " + section + ": [[" + section +
           "]] tables are set in the scene file; --set reaches the sections' keys only";
  if (!find_scene_section(section))
    return where + ": " + printable(section) + ": " + unknown_section_error(section);
  const SceneField* spec = find_scene_field(section, key);
  if (!spec) return where + ": " + printable(lhs) + ": " + unknown_key_error(section, key);
  // The value in TOML syntax; failing that, a bare word stands for a string
  // (--set material.model=linear) where the key takes one.
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
    // A number TOML refuses (beyond a double's range) is not a bare word, where the key
    // takes no text.
    if (spec->type != FieldType::Text && spec->type != FieldType::Choice)
      if (const std::string e = scene_io::unreadable_number(rhs); !e.empty())
        return where + ": " + lhs + ": " + e;
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
  if (auto r = apply_key(s, *spec, *parsed.get("v"), material); !r.empty())
    return where + ": " + lhs + ": " + r;
  *lhs_out = lhs;
  return "";
}

}  // namespace

std::string apply_overrides(SceneDef& s, std::span<const std::string> assignments) {
  // Every override is read first, then the scene is checked once as a whole: a state that
  // is valid only after several of them (a box's min and max, a term and its keys) is
  // reachable in any order. Errors name the --set of the key they blame.
  SceneDef candidate = s;
  MaterialInput material;
  std::map<std::string, std::string> written;  // "section.key" -> its last --set
  for (const std::string& assignment : assignments) {
    std::string lhs;
    if (auto e = read_override(candidate, material, assignment, &lhs); !e.empty()) return e;
    written[lhs] = assignment;
  }
  if (assignments.empty()) return "";
  auto where = [&](const std::string& key) {
    const auto it = written.find(key);
    return "--set " + printable(it != written.end() ? it->second : assignments.back()) + ": ";
  };
  auto written_in = [&](std::string_view section) -> std::string {
    for (const auto& [key, assignment] : written)
      if (key.rfind(std::string(section) + ".", 0) == 0) return key;
    return "";
  };
  // Asking for self-contact where it cannot run is refused; another key that makes it
  // unable to ([mass_spring], [fixed]) leaves it inactive.
  if (const std::string key = written_in("self_contact"); !key.empty())
    if (const auto problem = self_contact_refusal(candidate))
      return where(key) + problem->key + ": " + problem->reason;
  if (auto r = apply_material(candidate, material); !r.empty())
    return where(r.substr(0, r.find(':'))) + r;
  // A new file, path, scale or shape is read now, relative to the current directory (the
  // scene's own files were resolved when it was loaded).
  for (const char* key : {"mesh.file", "mesh.path_id", "mesh.scale", "mesh.shape"})
    if (written.count(key)) {
      if (auto r = scene_io::load_shape_files(candidate, "--set"); !r.empty())
        return where(r.substr(0, r.find(':'))) + r;
      break;
    }
  if (const auto problem = find_scene_problem(candidate)) {
    const Blame b = blame(*problem, [&](const std::string& k) { return written.count(k) > 0; });
    return where(b.key) + b.message;
  }
  s = std::move(candidate);
  return "";
}

std::string apply_override(SceneDef& s, std::string_view assignment) {
  const std::string one(assignment);
  return apply_overrides(s, std::span<const std::string>(&one, 1));
}

std::string scene_to_toml(const SceneDef& s) {
  // Every key the scene keeps is written, and a switched-off term keeps its values under
  // `enabled = false`, so that parsing the text gives back exactly this scene. Self-contact
  // writes whether it runs (self_contact_on): asked for where it cannot, it is inactive,
  // and the file says so rather than ask for what its reader would refuse.
  std::string out = "name = " + scene_io::toml_string(s.name) + "\n";
  SceneDef written = s;
  written.has_self_contact = s.self_contact_on();
  for (const auto& section : scene_sections()) {
    out += "\n[" + std::string(section.name) + "]\n";
    for (const auto& k : scene_fields())
      if (k.kept && std::string_view(k.section) == section.name)
        out += std::string(k.key) + " = " + scene_io::write_field(k, written) + "\n";
  }
  return out + scene_io::body_tables_to_toml(s) + scene_io::traction_tables_to_toml(s);
}

}  // namespace invfree

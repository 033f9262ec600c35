// gmsh .msh (ASCII 2.x and 4.1) and Wavefront .obj readers: line by line, each line split into
// words, every malformed line one error naming the file and the line.
#include "scene_io/mesh_file.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "scene_io/error_text.h"

namespace invfree {
namespace {

// The file's lines, each split into whitespace-separated words.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  // The next line's words (possibly none); false at the end of the text.
  bool next(std::vector<std::string_view>& words) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    words.clear();
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_space(line[i])) ++i;
      const std::size_t from = i;
      while (i < line.size() && !is_space(line[i])) ++i;
      if (i > from) words.push_back(line.substr(from, i - from));
    }
    return true;
  }
  // The next line that has words; false at the end.
  bool next_nonblank(std::vector<std::string_view>& words) {
    while (next(words))
      if (!words.empty()) return true;
    return false;
  }
  int line() const { return line_; }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  }
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

std::optional<double> to_double(std::string_view w) {
  if (!w.empty() && w[0] == '+') w.remove_prefix(1);
  double x = 0;
  const auto r = std::from_chars(w.data(), w.data() + w.size(), x);
  if (r.ec != std::errc() || r.ptr != w.data() + w.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

std::optional<long long> to_int(std::string_view w) {
  if (!w.empty() && w[0] == '+') w.remove_prefix(1);
  long long x = 0;
  const auto r = std::from_chars(w.data(), w.data() + w.size(), x);
  if (r.ec != std::errc() || r.ptr != w.data() + w.size()) return std::nullopt;
  return x;
}

std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// The z check of both formats: every z within 1e-12 × the bounding-box diagonal of 0.
// Returns the index of the first node that is not, or -1.
int first_off_plane(const std::vector<Vec2>& xy, const std::vector<double>& z) {
  if (xy.empty()) return -1;
  double lo[3] = {xy[0].x(), xy[0].y(), z[0]}, hi[3] = {lo[0], lo[1], lo[2]};
  for (std::size_t i = 0; i < xy.size(); ++i) {
    const double p[3] = {xy[i].x(), xy[i].y(), z[i]};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  const double size = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  for (std::size_t i = 0; i < z.size(); ++i)
    if (std::abs(z[i]) > 1e-12 * size) return static_cast<int>(i);
  return -1;
}

// gmsh element types by the number of their nodes: points and lines are ignored, the rest
// (2D and 3D) refused by name.
bool is_point_or_line(long long type) {
  return type == 15 || type == 1 || type == 8 || type == 26 || type == 27 || type == 28;
}
std::string element_type_name(long long type) {
  switch (type) {
    case 3:
      return "4-node quadrangle";
    case 4:
      return "4-node tetrahedron";
    case 5:
      return "8-node hexahedron";
    case 6:
      return "6-node prism";
    case 7:
      return "5-node pyramid";
    case 9:
      return "6-node second-order triangle";
    case 10:
      return "9-node second-order quadrangle";
    case 16:
      return "8-node second-order quadrangle";
    case 20:
    case 21:
    case 22:
    case 23:
    case 24:
    case 25:
      return "higher-order triangle";
    case 11:
    case 29:
    case 30:
    case 31:
      return "higher-order tetrahedron";
    default:
      return "";
  }
}

class MshReader {
 public:
  MshReader(std::string_view text, const std::string& name, ShapeFile& out)
      : in_(text), name_(name), out_(out) {}

  std::string read() {
    bool format = false, nodes = false, elements = false;
    while (in_.next_nonblank(w_)) {
      const std::string_view section = w_[0];
      if (section.empty() || section[0] != '$' || w_.size() != 1)
        return fail("expected a section name such as $Nodes, got " + quote_words());
      if (!format && section != "$MeshFormat") return fail("expected $MeshFormat first");
      std::string e;
      if (section == "$MeshFormat") {
        if (format) return fail("a second $MeshFormat");
        e = mesh_format();
        format = true;
      } else if (section == "$Nodes") {
        if (nodes) return fail("a second $Nodes section");
        e = version4_ ? nodes4() : nodes2();
        nodes = true;
      } else if (section == "$Elements") {
        if (elements) return fail("a second $Elements section");
        e = version4_ ? elements4() : elements2();
        elements = true;
      } else {
        e = skip_section(section);
      }
      if (!e.empty()) return e;
      if (section == "$MeshFormat" || section == "$Nodes" || section == "$Elements")
        if (auto e2 = end_of(section); !e2.empty()) return e2;
    }
    if (!format) return name_ + ": not a gmsh .msh file (no $MeshFormat)";
    if (!nodes) return name_ + ": no $Nodes section";
    if (!elements) return name_ + ": no $Elements section";
    return finish();
  }

 private:
  std::string fail(const std::string& what) const {
    return name_ + ":" + std::to_string(in_.line()) + ": " + what;
  }
  std::string quote_words() const {
    std::string s;
    for (auto w : w_) (s += s.empty() ? "" : " ") += w;
    return quoted(printable(s, 40));
  }
  // The next line, which must hold `count` numbers (words parsed by the caller).
  bool line_with(std::size_t count) { return in_.next_nonblank(w_) && w_.size() == count; }

  std::string end_of(std::string_view section) {
    const std::string want = "$End" + std::string(section.substr(1));
    if (!in_.next_nonblank(w_)) return name_ + ": the file ends before " + want;
    if (w_.size() != 1 || w_[0] != want) return fail("expected " + want + ", got " + quote_words());
    return "";
  }

  std::string skip_section(std::string_view section) {
    const std::string want = "$End" + std::string(section.substr(1));
    while (in_.next(w_))
      if (!w_.empty() && w_[0] == want) return "";
    return name_ + ": the file ends before " + want;
  }

  std::string mesh_format() {
    if (!in_.next_nonblank(w_) || w_.size() != 3)
      return fail("expected 'version file-type data-size' (e.g. 4.1 0 8)");
    const std::string_view version = w_[0];
    if (w_[1] == "1") return name_ + ": binary .msh is not supported; save as ASCII";
    if (w_[1] != "0") return fail("file-type must be 0 (ASCII), got " + quote_words());
    if (version.substr(0, 2) == "2.") {
      version4_ = false;
    } else if (version == "4.1") {
      version4_ = true;
    } else {
      return fail("unsupported .msh version " + quoted(printable(version, 20)) +
                  " (2.x or 4.1; gmsh saves either with -format msh22 or msh41)");
    }
    return "";
  }

  // A count on its own line.
  std::string count_line(long long& n, const char* what) {
    if (!in_.next_nonblank(w_) || w_.size() != 1)
      return fail(std::string("expected the number of ") + what);
    const auto v = to_int(w_[0]);
    if (!v || *v < 0) return fail(std::string("expected the number of ") + what);
    n = *v;
    return "";
  }

  std::string add_node(long long tag, double x, double y, double z) {
    if (!tag_index_.emplace(tag, static_cast<int>(out_.nodes.size())).second)
      return fail("node tag " + std::to_string(tag) + " appears twice");
    out_.nodes.emplace_back(x, y);
    tags_.push_back(tag);
    z_.push_back(z);
    node_lines_.push_back(in_.line());
    return "";
  }

  std::string nodes2() {
    long long n = 0;
    if (auto e = count_line(n, "nodes"); !e.empty()) return e;
    for (long long i = 0; i < n; ++i) {
      if (!line_with(4)) return fail("expected 4 numbers in a node line (tag x y z)");
      const auto tag = to_int(w_[0]);
      const auto x = to_double(w_[1]), y = to_double(w_[2]), z = to_double(w_[3]);
      if (!tag || !x || !y || !z) return fail("expected 4 numbers in a node line (tag x y z)");
      if (auto e = add_node(*tag, *x, *y, *z); !e.empty()) return e;
    }
    return "";
  }

  std::string nodes4() {
    if (!line_with(4))
      return fail("expected 4 numbers: numEntityBlocks numNodes minNodeTag maxNodeTag");
    long long blocks = 0, total = 0;
    {
      const auto b = to_int(w_[0]), t = to_int(w_[1]);
      if (!b || !t || *b < 0 || *t < 0 || !to_int(w_[2]) || !to_int(w_[3]))
        return fail("expected 4 numbers: numEntityBlocks numNodes minNodeTag maxNodeTag");
      blocks = *b;
      total = *t;
    }
    long long seen = 0;
    for (long long b = 0; b < blocks; ++b) {
      if (!line_with(4))
        return fail(
            "expected 4 numbers in a node block header: entityDim entityTag parametric "
            "numNodesInBlock");
      const auto dim = to_int(w_[0]), param = to_int(w_[2]), n = to_int(w_[3]);
      if (!dim || !to_int(w_[1]) || !param || !n || *n < 0 || *dim < 0 || *dim > 3 ||
          (*param != 0 && *param != 1))
        return fail(
            "expected 4 numbers in a node block header: entityDim entityTag parametric "
            "numNodesInBlock");
      std::vector<long long> tags;
      std::vector<int> lines;
      for (long long i = 0; i < *n; ++i) {
        if (!line_with(1) || !to_int(w_[0])) return fail("expected one node tag on the line");
        tags.push_back(*to_int(w_[0]));
      }
      const std::size_t want = 3 + (*param ? static_cast<std::size_t>(*dim) : 0);
      for (long long i = 0; i < *n; ++i) {
        const std::string msg = "expected " + std::to_string(want) +
                                " numbers in a node line (x y z" +
                                (want > 3 ? " and the parametric coordinates)" : ")");
        if (!line_with(want)) return fail(msg);
        const auto x = to_double(w_[0]), y = to_double(w_[1]), z = to_double(w_[2]);
        if (!x || !y || !z) return fail(msg);
        if (auto e = add_node(tags[static_cast<std::size_t>(i)], *x, *y, *z); !e.empty()) return e;
      }
      seen += *n;
    }
    if (seen != total)
      return fail("the node blocks hold " + std::to_string(seen) + " nodes, the header says " +
                  std::to_string(total));
    return "";
  }

  // One element: type and node tags (the words after the element's tag and, in v2, its tags).
  std::string element(long long type, std::span<const std::string_view> nodes) {
    if (type == 2) {
      if (nodes.size() != 3)
        return fail("a triangle (type 2) needs 3 node tags, got " + std::to_string(nodes.size()));
      std::array<long long, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const auto v = to_int(nodes[static_cast<std::size_t>(k)]);
        if (!v)
          return fail("expected a node tag, got " +
                      quoted(printable(nodes[static_cast<std::size_t>(k)], 20)));
        t[static_cast<std::size_t>(k)] = *v;
      }
      tri_tags_.push_back(t);
      tri_lines_.push_back(in_.line());
      return "";
    }
    if (is_point_or_line(type)) return "";
    const std::string what = element_type_name(type);
    return fail("element type " + std::to_string(type) + (what.empty() ? "" : " (" + what + ")") +
                " is not supported: only 3-node triangles (type 2), with points and lines ignored");
  }

  std::string elements2() {
    long long n = 0;
    if (auto e = count_line(n, "elements"); !e.empty()) return e;
    for (long long i = 0; i < n; ++i) {
      const char* msg = "expected an element line: tag type number-of-tags tags... nodes...";
      if (!in_.next_nonblank(w_) || w_.size() < 3) return fail(msg);
      const auto tag = to_int(w_[0]), type = to_int(w_[1]), ntags = to_int(w_[2]);
      if (!tag || !type || !ntags || *ntags < 0 || static_cast<std::size_t>(*ntags) + 3 > w_.size())
        return fail(msg);
      const std::vector<std::string_view> words = w_;
      if (auto e = element(*type, std::span(words).subspan(3 + static_cast<std::size_t>(*ntags)));
          !e.empty())
        return e;
    }
    return "";
  }

  std::string elements4() {
    const char* head =
        "expected 4 numbers: numEntityBlocks numElements minElementTag maxElementTag";
    if (!line_with(4)) return fail(head);
    const auto blocks = to_int(w_[0]), total = to_int(w_[1]);
    if (!blocks || !total || *blocks < 0 || *total < 0 || !to_int(w_[2]) || !to_int(w_[3]))
      return fail(head);
    long long seen = 0;
    for (long long b = 0; b < *blocks; ++b) {
      const char* bh =
          "expected 4 numbers in an element block header: entityDim entityTag elementType "
          "numElementsInBlock";
      if (!line_with(4)) return fail(bh);
      const auto type = to_int(w_[2]), n = to_int(w_[3]);
      if (!to_int(w_[0]) || !to_int(w_[1]) || !type || !n || *n < 0) return fail(bh);
      for (long long i = 0; i < *n; ++i) {
        if (!in_.next_nonblank(w_) || w_.size() < 2 || !to_int(w_[0]))
          return fail("expected an element line: tag and node tags");
        const std::vector<std::string_view> words = w_;
        if (auto e = element(*type, std::span(words).subspan(1)); !e.empty()) return e;
      }
      seen += *n;
    }
    if (seen != *total)
      return fail("the element blocks hold " + std::to_string(seen) +
                  " elements, the header says " + std::to_string(*total));
    return "";
  }

  std::string finish() {
    if (const int i = first_off_plane(out_.nodes, z_); i >= 0)
      return name_ + ":" + std::to_string(node_lines_[static_cast<std::size_t>(i)]) + ": node " +
             std::to_string(tags_[static_cast<std::size_t>(i)]) +
             " has z = " + format_number(z_[static_cast<std::size_t>(i)]) +
             " (the mesh must lie in z = 0)";
    if (tri_tags_.empty()) return name_ + ": no triangles (element type 2)";
    for (std::size_t k = 0; k < tri_tags_.size(); ++k) {
      std::array<int, 3> t{};
      for (int j = 0; j < 3; ++j) {
        const auto it = tag_index_.find(tri_tags_[k][static_cast<std::size_t>(j)]);
        if (it == tag_index_.end())
          return name_ + ":" + std::to_string(tri_lines_[k]) + ": node " +
                 std::to_string(tri_tags_[k][static_cast<std::size_t>(j)]) + " is not in $Nodes";
        t[static_cast<std::size_t>(j)] = it->second;
      }
      out_.triangles.push_back(t);
    }
    return "";
  }

  LineReader in_;
  const std::string& name_;
  ShapeFile& out_;
  std::vector<std::string_view> w_;
  bool version4_ = false;
  std::unordered_map<long long, int> tag_index_;
  std::vector<long long> tags_;
  std::vector<double> z_;
  std::vector<int> node_lines_;
  std::vector<std::array<long long, 3>> tri_tags_;
  std::vector<int> tri_lines_;
};

}  // namespace

std::string parse_msh(std::string_view text, const std::string& name, ShapeFile& out) {
  out.nodes.clear();
  out.triangles.clear();
  MshReader reader(text, name, out);
  std::string e = reader.read();
  if (!e.empty()) {
    out.nodes.clear();
    out.triangles.clear();
  }
  return e;
}

std::string parse_obj(std::string_view text, const std::string& name, ShapeFile& out) {
  out.nodes.clear();
  out.triangles.clear();
  LineReader in(text);
  std::vector<std::string_view> w;
  std::vector<double> z;
  std::vector<int> node_lines;
  std::vector<std::array<long long, 3>> faces;  // 0-based, maybe past the last vertex
  std::vector<int> face_lines;
  auto fail = [&](const std::string& what) {
    out.nodes.clear();
    return name + ":" + std::to_string(in.line()) + ": " + what;
  };
  while (in.next(w)) {
    if (w.empty() || w[0][0] == '#') continue;
    if (w[0] == "v") {
      // x y z, optionally w or an r g b colour.
      const char* msg = "expected 'v x y z' (3 numbers, or 4 with w, or 6 with a colour)";
      if (w.size() != 4 && w.size() != 5 && w.size() != 7) return fail(msg);
      std::optional<double> c[3];
      for (int k = 0; k < 3; ++k) c[k] = to_double(w[static_cast<std::size_t>(k) + 1]);
      if (!c[0] || !c[1] || !c[2]) return fail(msg);
      for (std::size_t k = 4; k < w.size(); ++k)
        if (!to_double(w[k])) return fail(msg);
      out.nodes.emplace_back(*c[0], *c[1]);
      z.push_back(*c[2]);
      node_lines.push_back(in.line());
    } else if (w[0] == "f") {
      if (w.size() > 4)
        return fail("a face with " + std::to_string(w.size() - 1) +
                    " vertices: only triangles are read (triangulate the mesh first)");
      if (w.size() < 4) return fail("a face needs 3 vertices, got " + std::to_string(w.size() - 1));
      std::array<long long, 3> f{};
      for (std::size_t k = 0; k < 3; ++k) {
        const std::string_view word = w[k + 1];
        const std::string_view index = word.substr(0, word.find('/'));
        const auto v = to_int(index);
        if (!v || *v == 0)
          return fail("expected a vertex index (1, 1/2, 1/2/3, 1//3 or negative), got " +
                      quoted(printable(word, 20)));
        const long long count = static_cast<long long>(out.nodes.size());
        const long long i = *v > 0 ? *v - 1 : count + *v;
        if (i < 0)
          return fail("vertex index " + std::to_string(*v) + " points before the first vertex (" +
                      std::to_string(count) + " so far)");
        f[k] = i;
      }
      faces.push_back(f);
      face_lines.push_back(in.line());
    } else if (w[0] == "vt" || w[0] == "vn" || w[0] == "vp" || w[0] == "o" || w[0] == "g" ||
               w[0] == "s" || w[0] == "l" || w[0] == "usemtl" || w[0] == "mtllib") {
      continue;
    } else {
      return fail("unknown statement " + quoted(printable(w[0], 20)) +
                  " (read: v, f; ignored: vt, vn, vp, o, g, s, l, usemtl, mtllib, #)");
    }
  }
  if (const int i = first_off_plane(out.nodes, z); i >= 0) {
    const std::string e = name + ":" + std::to_string(node_lines[static_cast<std::size_t>(i)]) +
                          ": vertex " + std::to_string(i + 1) +
                          " has z = " + format_number(z[static_cast<std::size_t>(i)]) +
                          " (the mesh must lie in z = 0)";
    out.nodes.clear();
    return e;
  }
  if (faces.empty()) {
    out.nodes.clear();
    return name + ": no triangles (no 'f' lines)";
  }
  const long long count = static_cast<long long>(out.nodes.size());
  for (std::size_t k = 0; k < faces.size(); ++k) {
    for (long long i : faces[k])
      if (i >= count) {
        out.nodes.clear();
        out.triangles.clear();
        return name + ":" + std::to_string(face_lines[k]) + ": vertex " + std::to_string(i + 1) +
               " does not exist (the file has " + std::to_string(count) + ")";
      }
    out.triangles.push_back({static_cast<int>(faces[k][0]), static_cast<int>(faces[k][1]),
                             static_cast<int>(faces[k][2])});
  }
  return "";
}

}  // namespace invfree

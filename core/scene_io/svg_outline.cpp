// SVG outlines to polygons. Every shape element is first written as path data (a <rect> with
// rx/ry as four lines and four arcs, a <circle> or <ellipse> as two arcs, a <polygon> as
// "M points Z"), so one parser and one flattener serve them all. Two passes: the segments of
// every used element in the drawing's coordinates (transforms applied; Bézier control points
// transform exactly, an arc keeps its centre form and matrix), then the bounding box that
// sets the tolerance, then the flattening of the closed subpaths.
#include "scene_io/svg_outline.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <numbers>
#include <pugixml.hpp>
#include <utility>

#include "scene_io/error_text.h"

namespace invfree {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kMaxDepth = 256;                  // nesting of groups
constexpr std::size_t kMaxPoints = 20'000'000;  // flattened points in all

// x' = a x + c y + e, y' = b x + d y + f (SVG's matrix(a b c d e f)).
struct Affine {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;
  Vec2 apply(const Vec2& p) const { return {a * p.x() + c * p.y() + e, b * p.x() + d * p.y() + f}; }
  Vec2 linear(const Vec2& p) const { return {a * p.x() + c * p.y(), b * p.x() + d * p.y()}; }
  // this ∘ o: o applied first.
  Affine operator*(const Affine& o) const {
    return {a * o.a + c * o.b, b * o.a + d * o.b,     a * o.c + c * o.d,
            b * o.c + d * o.d, a * o.e + c * o.f + e, b * o.e + d * o.f + f};
  }
};

// The largest singular value of [[a c] [b d]].
double max_stretch(double a, double b, double c, double d) {
  const double s = 0.5 * (a * a + b * b + c * c + d * d);
  const double det = a * d - b * c;
  return std::sqrt(s + std::sqrt(std::max(0.0, s * s - det * det)));
}

struct Segment {
  enum Kind { Line, Quad, Cubic, Arc } kind = Line;
  Vec2 p[4] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero(),
               Vec2::Zero()};  // drawing coordinates:
                               // p[0] start, the last used one the end
  // Arc: the ellipse x(t) = centre + u cos t + v sin t (drawing coordinates), t from theta1
  // over dtheta.
  Vec2 centre = Vec2::Zero(), u = Vec2::Zero(), v = Vec2::Zero();
  double theta1 = 0, dtheta = 0;
  Vec2 end() const {
    return kind == Line ? p[1] : kind == Quad ? p[2] : kind == Cubic ? p[3] : p[1];
  }
};

struct Subpath {
  Vec2 start;
  std::vector<Segment> segments;
  bool closed = false;  // ended by Z/z
};

struct Element {
  std::vector<Subpath> subpaths;
  FillRule rule = FillRule::NonZero;
};

std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// ---------------------------------------------------------------------------------------
// Numbers, flags and separators of path data, points and transforms.
class Scanner {
 public:
  explicit Scanner(std::string_view s) : s_(s) {}
  void skip_space() {
    while (i_ < s_.size() && is_space(s_[i_])) ++i_;
  }
  void skip_separator() {  // whitespace, at most one comma, whitespace
    skip_space();
    if (i_ < s_.size() && s_[i_] == ',') ++i_;
    skip_space();
  }
  bool at_end() const { return i_ >= s_.size(); }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  void advance() { ++i_; }
  bool at_number() const {
    const char c = peek();
    return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
  }
  // A number in SVG's grammar ("-.5.5" is -0.5 then 0.5, "1e-3", "+2"); nullopt if none.
  std::optional<double> number() {
    std::size_t j = i_;
    if (j < s_.size() && (s_[j] == '+' || s_[j] == '-')) ++j;
    const std::size_t digits_from = j;
    while (j < s_.size() && is_digit(s_[j])) ++j;
    bool any = j > digits_from;
    if (j < s_.size() && s_[j] == '.') {
      const std::size_t frac_from = ++j;
      while (j < s_.size() && is_digit(s_[j])) ++j;
      any = any || j > frac_from;
    }
    if (!any) return std::nullopt;
    if (j < s_.size() && (s_[j] == 'e' || s_[j] == 'E')) {
      std::size_t k = j + 1;
      if (k < s_.size() && (s_[k] == '+' || s_[k] == '-')) ++k;
      if (k < s_.size() && is_digit(s_[k])) {
        while (k < s_.size() && is_digit(s_[k])) ++k;
        j = k;
      }
    }
    std::size_t from = i_;
    if (s_[from] == '+') ++from;
    double x = 0;
    const auto r = std::from_chars(s_.data() + from, s_.data() + j, x);
    if (r.ec != std::errc() || r.ptr != s_.data() + j || !std::isfinite(x)) return std::nullopt;
    i_ = j;
    return x;
  }
  // An arc flag: one character, 0 or 1, needing no separator after it ("a1 1 0 01 1 1").
  std::optional<bool> flag() {
    if (peek() == '0' || peek() == '1') return s_[i_++] == '1';
    return std::nullopt;
  }
  std::size_t position() const { return i_; }
  std::string_view rest_word() const {  // for errors: what stands where a number should
    if (at_end()) return "the end";
    return s_.substr(i_, 12);
  }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f';
  }
  static bool is_digit(char c) { return c >= '0' && c <= '9'; }
  std::string_view s_;
  std::size_t i_ = 0;
};

// ---------------------------------------------------------------------------------------
// Path data (SVG 1.1 §8.3) into subpaths, transformed by m. "" or the reason.
std::string parse_path_data(std::string_view d, const Affine& m, std::vector<Subpath>& out) {
  Scanner sc(d);
  Vec2 cur(0, 0), start(0, 0);  // element coordinates
  Vec2 last_cubic_ctrl(0, 0), last_quad_ctrl(0, 0);
  char prev = '\0';   // the previous command, upper case
  bool open = false;  // a subpath is under way
  auto begin_subpath = [&](const Vec2& p) {
    out.push_back(Subpath{m.apply(p), {}, false});
    open = true;
  };
  auto ensure_open = [&] {
    if (!open) begin_subpath(cur);  // a command after Z starts at the subpath's start
  };
  // A line or Bezier segment from the current point through `points` (drawing coordinates
  // once transformed); the last point becomes the current one.
  auto add_segment = [&](Segment::Kind kind, std::initializer_list<Vec2> points) {
    ensure_open();
    Segment s;
    s.kind = kind;
    s.p[0] = m.apply(cur);
    int k = 1;
    for (const Vec2& p : points) s.p[k++] = m.apply(p);
    out.back().segments.push_back(s);
    cur = *(points.end() - 1);
  };
  auto add_line = [&](const Vec2& to) { add_segment(Segment::Line, {to}); };
  auto add_arc = [&](double rx, double ry, double phi_deg, bool large, bool sweep, const Vec2& to) {
    ensure_open();
    // SVG 1.1 F.6.2: the same endpoints draw nothing; a zero radius draws a line.
    if (cur == to) return;
    rx = std::abs(rx);
    ry = std::abs(ry);
    if (rx == 0 || ry == 0) {
      add_line(to);
      return;
    }
    // F.6.5: from the endpoints to the centre, with F.6.6's radius correction.
    const double phi = phi_deg * kPi / 180.0, cp = std::cos(phi), sp = std::sin(phi);
    const double dx2 = 0.5 * (cur.x() - to.x()), dy2 = 0.5 * (cur.y() - to.y());
    const double x1p = cp * dx2 + sp * dy2, y1p = -sp * dx2 + cp * dy2;
    const double lambda = x1p * x1p / (rx * rx) + y1p * y1p / (ry * ry);
    if (lambda > 1) {
      rx *= std::sqrt(lambda);
      ry *= std::sqrt(lambda);
    }
    const double num = rx * rx * ry * ry - rx * rx * y1p * y1p - ry * ry * x1p * x1p;
    const double den = rx * rx * y1p * y1p + ry * ry * x1p * x1p;
    double coef = den > 0 ? std::sqrt(std::max(0.0, num / den)) : 0.0;
    if (large == sweep) coef = -coef;
    const double cxp = coef * rx * y1p / ry, cyp = -coef * ry * x1p / rx;
    const Vec2 centre(cp * cxp - sp * cyp + 0.5 * (cur.x() + to.x()),
                      sp * cxp + cp * cyp + 0.5 * (cur.y() + to.y()));
    auto angle = [](double ux, double uy, double vx, double vy) {
      return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
    };
    const double ux = (x1p - cxp) / rx, uy = (y1p - cyp) / ry;
    const double vx = (-x1p - cxp) / rx, vy = (-y1p - cyp) / ry;
    const double theta1 = angle(1, 0, ux, uy);
    double dtheta = angle(ux, uy, vx, vy);
    if (!sweep && dtheta > 0) dtheta -= 2 * kPi;
    if (sweep && dtheta < 0) dtheta += 2 * kPi;
    Segment s;
    s.kind = Segment::Arc;
    s.p[0] = m.apply(cur);
    s.p[1] = m.apply(to);
    s.centre = m.apply(centre);
    s.u = m.linear(Vec2(cp * rx, sp * rx));
    s.v = m.linear(Vec2(-sp * ry, cp * ry));
    s.theta1 = theta1;
    s.dtheta = dtheta;
    out.back().segments.push_back(s);
    cur = to;
  };
  auto fail = [&](const std::string& what) {
    return what + " at character " + std::to_string(sc.position() + 1);
  };
  sc.skip_space();
  if (sc.at_end()) return "";  // empty path data draws nothing
  char cmd = '\0';
  while (true) {
    sc.skip_space();
    if (sc.at_end()) break;
    const char c = sc.peek();
    const std::string got = "got '" + printable(sc.rest_word()) + "'";
    if (std::string_view("MmLlHhVvCcSsQqTtAaZz").find(c) != std::string_view::npos) {
      if (prev == '\0' && c != 'M' && c != 'm') return fail("path data must begin with M or m");
      cmd = c;
      sc.advance();
    } else if (sc.at_number() && cmd != '\0' && cmd != 'Z' && cmd != 'z') {
      // An implicit repeat of the previous command; after a moveto, a lineto.
      if (cmd == 'M') cmd = 'L';
      if (cmd == 'm') cmd = 'l';
    } else if (cmd == '\0') {
      return fail("path data must begin with M or m, " + got);
    } else if (cmd == 'Z' || cmd == 'z') {
      return fail(std::string("expected a command after '") + cmd + "', " + got);
    } else {
      return fail("expected a command or a number, " + got);
    }
    if (prev == '\0' && cmd != 'M' && cmd != 'm') return fail("path data must begin with M or m");
    const bool rel = cmd >= 'a' && cmd <= 'z';
    const char up = static_cast<char>(rel ? cmd - 'a' + 'A' : cmd);
    const Vec2 base = rel ? cur : Vec2(0, 0);
    std::vector<double> v;
    auto numbers = [&](int count) -> bool {
      for (int k = 0; k < count; ++k) {
        sc.skip_separator();
        const auto x = sc.number();
        if (!x) return false;
        v.push_back(*x);
      }
      return true;
    };
    const std::string expected = std::string("expected a number after '") + cmd + "', got '";
    auto number_error = [&] { return fail(expected + printable(sc.rest_word()) + "'"); };
    switch (up) {
      case 'Z': {
        if (open) {
          if (cur != start) add_line(start);
          out.back().closed = true;
        }
        open = false;
        cur = start;
        break;
      }
      case 'M': {
        if (!numbers(2)) return number_error();
        cur = base + Vec2(v[0], v[1]);
        start = cur;
        begin_subpath(cur);
        break;
      }
      case 'L':
        if (!numbers(2)) return number_error();
        add_line(base + Vec2(v[0], v[1]));
        break;
      case 'H':
        if (!numbers(1)) return number_error();
        add_line(Vec2(rel ? cur.x() + v[0] : v[0], cur.y()));
        break;
      case 'V':
        if (!numbers(1)) return number_error();
        add_line(Vec2(cur.x(), rel ? cur.y() + v[0] : v[0]));
        break;
      case 'C':
      case 'S': {
        Vec2 c1, c2, to;
        if (up == 'C') {
          if (!numbers(6)) return number_error();
          c1 = base + Vec2(v[0], v[1]);
          c2 = base + Vec2(v[2], v[3]);
          to = base + Vec2(v[4], v[5]);
        } else {
          if (!numbers(4)) return number_error();
          c1 = (prev == 'C' || prev == 'S') ? Vec2(2 * cur - last_cubic_ctrl) : cur;
          c2 = base + Vec2(v[0], v[1]);
          to = base + Vec2(v[2], v[3]);
        }
        add_segment(Segment::Cubic, {c1, c2, to});
        last_cubic_ctrl = c2;
        break;
      }
      case 'Q':
      case 'T': {
        Vec2 c1, to;
        if (up == 'Q') {
          if (!numbers(4)) return number_error();
          c1 = base + Vec2(v[0], v[1]);
          to = base + Vec2(v[2], v[3]);
        } else {
          if (!numbers(2)) return number_error();
          c1 = (prev == 'Q' || prev == 'T') ? Vec2(2 * cur - last_quad_ctrl) : cur;
          to = base + Vec2(v[0], v[1]);
        }
        add_segment(Segment::Quad, {c1, to});
        last_quad_ctrl = c1;
        break;
      }
      case 'A': {
        if (!numbers(3)) return number_error();
        sc.skip_separator();
        const auto large = sc.flag();
        if (!large) return fail(std::string("expected an arc flag (0 or 1) after '") + cmd + "'");
        sc.skip_separator();
        const auto sweep = sc.flag();
        if (!sweep) return fail(std::string("expected an arc flag (0 or 1) after '") + cmd + "'");
        if (!numbers(2)) return number_error();
        add_arc(v[0], v[1], v[2], *large, *sweep, base + Vec2(v[3], v[4]));
        break;
      }
    }
    prev = up;
    sc.skip_separator();
  }
  return "";
}

// A transform list (SVG 1.1 §7.6) into m. "" or the reason.
std::string parse_transform(std::string_view text, Affine& m) {
  Scanner sc(text);
  Affine total;
  while (true) {
    sc.skip_separator();
    if (sc.at_end()) break;
    std::string name;
    while (!sc.at_end() &&
           ((sc.peek() >= 'a' && sc.peek() <= 'z') || (sc.peek() >= 'A' && sc.peek() <= 'Z'))) {
      name += sc.peek();
      sc.advance();
    }
    sc.skip_space();
    if (name.empty() || sc.peek() != '(')
      return "expected matrix, translate, scale, rotate, skewX or skewY followed by '(' at "
             "character " +
             std::to_string(sc.position() + 1);
    sc.advance();
    std::vector<double> a;
    while (true) {
      sc.skip_separator();
      if (sc.peek() == ')') break;
      const auto x = sc.number();
      if (!x)
        return name + "(...): expected a number or ')' at character " +
               std::to_string(sc.position() + 1);
      a.push_back(*x);
    }
    sc.advance();
    auto want = [&](std::initializer_list<std::size_t> counts) {
      for (std::size_t n : counts)
        if (a.size() == n) return true;
      return false;
    };
    const std::string bad =
        name + "(...): wrong number of values (" + std::to_string(a.size()) + ")";
    Affine t;
    if (name == "matrix") {
      if (!want({6})) return bad;
      t = {a[0], a[1], a[2], a[3], a[4], a[5]};
    } else if (name == "translate") {
      if (!want({1, 2})) return bad;
      t.e = a[0];
      t.f = a.size() > 1 ? a[1] : 0.0;
    } else if (name == "scale") {
      if (!want({1, 2})) return bad;
      t.a = a[0];
      t.d = a.size() > 1 ? a[1] : a[0];
    } else if (name == "rotate") {
      if (!want({1, 3})) return bad;
      const double r = a[0] * kPi / 180.0;
      const Affine rot{std::cos(r), std::sin(r), -std::sin(r), std::cos(r), 0, 0};
      if (a.size() == 3) {
        t = Affine{1, 0, 0, 1, a[1], a[2]} * rot * Affine{1, 0, 0, 1, -a[1], -a[2]};
      } else {
        t = rot;
      }
    } else if (name == "skewX") {
      if (!want({1})) return bad;
      t.c = std::tan(a[0] * kPi / 180.0);
    } else if (name == "skewY") {
      if (!want({1})) return bad;
      t.b = std::tan(a[0] * kPi / 180.0);
    } else {
      return "unknown transform '" + printable(name) + "'";
    }
    total = total * t;
  }
  m = total;
  return "";
}

// A length attribute: a number, optionally "px" (user units). nullopt: missing.
struct Length {
  double value = 0;
  bool present = false;
  std::string error;
};
Length read_length(const pugi::xml_node& node, const char* attr) {
  const pugi::xml_attribute a = node.attribute(attr);
  if (!a) return {};
  std::string_view text = a.value();
  Scanner sc(text);
  sc.skip_space();
  const auto x = sc.number();
  std::string_view rest = text.substr(std::min(text.size(), sc.position()));
  while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t')) rest.remove_suffix(1);
  if (!x || !(rest.empty() || rest == "px"))
    return {
        0, false,
        std::string(attr) + ": expected a number in user units, got " + quoted(printable(text))};
  return {*x, true, ""};
}

std::string local_name(const pugi::xml_node& n) {
  std::string name = n.name();
  const auto colon = name.find(':');
  return colon == std::string::npos ? name : name.substr(colon + 1);
}

bool is_shape(const std::string& name) {
  return name == "path" || name == "polygon" || name == "polyline" || name == "rect" ||
         name == "circle" || name == "ellipse";
}
bool is_never_drawn(const std::string& name) {
  return name == "defs" || name == "clipPath" || name == "mask" || name == "symbol" ||
         name == "pattern" || name == "marker" || name == "metadata" || name == "title" ||
         name == "desc" || name == "style" || name == "script";
}

// The fill rule a node sets (its `style` property before its attribute).
enum class RuleSet { None, NonZero, EvenOdd, Bad };
RuleSet own_fill_rule(const pugi::xml_node& n) {
  std::string value;
  bool found = false;
  const std::string_view style = n.attribute("style").value();
  std::size_t i = 0;
  while (i < style.size()) {
    std::size_t j = style.find(';', i);
    if (j == std::string_view::npos) j = style.size();
    const std::string_view decl = style.substr(i, j - i);
    const std::size_t colon = decl.find(':');
    if (colon != std::string_view::npos) {
      auto trim = [](std::string_view s) {
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
          s.remove_prefix(1);
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
        return s;
      };
      if (trim(decl.substr(0, colon)) == "fill-rule") {
        value = std::string(trim(decl.substr(colon + 1)));
        found = true;
      }
    }
    i = j + 1;
  }
  if (!found && n.attribute("fill-rule")) {
    value = n.attribute("fill-rule").value();
    found = true;
  }
  if (!found || value == "inherit") return RuleSet::None;
  if (value == "evenodd") return RuleSet::EvenOdd;
  if (value == "nonzero") return RuleSet::NonZero;
  return RuleSet::Bad;
}

class Reader {
 public:
  Reader(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  std::string error_at(const pugi::xml_node& n, const std::string& what) const {
    std::string where = name_;
    const std::ptrdiff_t off = n.offset_debug();
    if (off >= 0 && static_cast<std::size_t>(off) <= text_.size())
      where += ":" + std::to_string(1 + std::count(text_.begin(), text_.begin() + off, '\n'));
    std::string tag = "<" + printable(local_name(n), 40);
    if (n.attribute("id")) tag += " id=" + quoted(printable(n.attribute("id").value(), 40));
    return where + ": " + tag + ">: " + what;
  }

  // Collects the shape elements under n (n itself included when `used`).
  std::string visit(const pugi::xml_node& n, const Affine& parent, FillRule rule, bool used,
                    const pugi::xml_node& target, int depth) {
    if (depth > kMaxDepth)
      return error_at(n, "nested more than " + std::to_string(kMaxDepth) + " deep");
    const std::string name = local_name(n);
    // Never-drawn subtrees are skipped, except on the way down to path_id's element.
    if (is_never_drawn(name) && n != target && (!target || used)) return "";
    used = used || n == target;
    Affine m = parent;
    if (const pugi::xml_attribute t = n.attribute("transform")) {
      Affine own;
      if (auto e = parse_transform(t.value(), own); !e.empty())
        return error_at(n, "transform: " + e);
      m = parent * own;
    }
    switch (own_fill_rule(n)) {
      case RuleSet::None:
        break;
      case RuleSet::NonZero:
        rule = FillRule::NonZero;
        break;
      case RuleSet::EvenOdd:
        rule = FillRule::EvenOdd;
        break;
      case RuleSet::Bad:
        return error_at(n, "fill-rule: expected nonzero or evenodd");
    }
    if (used && is_shape(name)) return shape(n, name, m, rule);
    for (const pugi::xml_node& child : n.children())
      if (child.type() == pugi::node_element)
        if (auto e = visit(child, m, rule, used, target, depth + 1); !e.empty()) return e;
    return "";
  }

  std::vector<Element> elements;

 private:
  std::string shape(const pugi::xml_node& n, const std::string& name, const Affine& m,
                    FillRule rule) {
    std::string d;
    if (name == "path") {
      d = n.attribute("d").value();
    } else if (name == "polygon" || name == "polyline") {
      const std::string_view pts = n.attribute("points").value();
      Scanner sc(pts);
      sc.skip_space();
      std::size_t count = 0;
      d = "M";
      while (!sc.at_end()) {
        const std::size_t at = sc.position();
        const auto x = sc.number();
        if (!x)
          return error_at(n, "points: expected a number, got '" + printable(sc.rest_word()) +
                                 "' at character " + std::to_string(at + 1));
        d += " " + format_number(*x);
        ++count;
        sc.skip_separator();
      }
      if (count % 2 != 0)
        return error_at(n, "points: " + std::to_string(count) +
                               " numbers, expected x,y pairs (an even number)");
      if (count == 0) return "";  // not drawn
      if (name == "polygon") d += " Z";
    } else {
      Length v[6];
      const char* names[6] = {"x", "y", "width", "height", "rx", "ry"};
      if (name == "circle") {
        names[0] = "cx", names[1] = "cy", names[2] = "r", names[3] = "";
      } else if (name == "ellipse") {
        names[0] = "cx", names[1] = "cy", names[2] = "rx", names[3] = "ry";
      }
      for (int k = 0; k < 6; ++k) {
        if (!*names[k] || (name != "rect" && k >= 4)) continue;
        v[k] = read_length(n, names[k]);
        if (!v[k].error.empty()) return error_at(n, v[k].error);
      }
      auto g = [](double x) { return format_number(x); };
      if (name == "rect") {
        const double x = v[0].value, y = v[1].value, w = v[2].value, h = v[3].value;
        if (w < 0 || h < 0) return error_at(n, "negative width or height");
        if (w == 0 || h == 0) return "";  // not drawn
        // SVG 1.1 §9.2: a missing rx is ry and the reverse; each at most half the side.
        double rx = v[4].present ? v[4].value : v[5].value;
        double ry = v[5].present ? v[5].value : v[4].value;
        if (rx < 0 || ry < 0) return error_at(n, "negative rx or ry");
        rx = std::min(rx, 0.5 * w);
        ry = std::min(ry, 0.5 * h);
        if (rx == 0 || ry == 0) {
          d = "M" + g(x) + "," + g(y) + " H" + g(x + w) + " V" + g(y + h) + " H" + g(x) + " Z";
        } else {
          const std::string arc = " A" + g(rx) + "," + g(ry) + " 0 0 1 ";
          d = "M" + g(x + rx) + "," + g(y) + " H" + g(x + w - rx) + arc + g(x + w) + "," +
              g(y + ry) + " V" + g(y + h - ry) + arc + g(x + w - rx) + "," + g(y + h) + " H" +
              g(x + rx) + arc + g(x) + "," + g(y + h - ry) + " V" + g(y + ry) + arc + g(x + rx) +
              "," + g(y) + " Z";
        }
      } else {
        const double cx = v[0].value, cy = v[1].value, rx = v[2].value;
        const double ry = name == "circle" ? rx : v[3].value;
        if (rx < 0 || ry < 0) return error_at(n, "negative radius");
        if (rx == 0 || ry == 0) return "";  // not drawn
        const std::string arc = " A" + g(rx) + "," + g(ry) + " 0 1 0 ";
        d = "M" + g(cx + rx) + "," + g(cy) + arc + g(cx - rx) + "," + g(cy) + arc + g(cx + rx) +
            "," + g(cy) + " Z";
      }
    }
    Element e;
    e.rule = rule;
    if (auto err = parse_path_data(d, m, e.subpaths); !err.empty())
      return error_at(n, "d: " + err);  // only <path>'s own data can be malformed
    elements.push_back(std::move(e));
    return "";
  }

  std::string_view text_;
  const std::string& name_;
};

// Flattened points of a subpath after its start (the start itself first).
void flatten(const Subpath& sp, double tol, std::vector<Vec2>& pts) {
  pts.push_back(sp.start);
  for (const Segment& s : sp.segments) {
    switch (s.kind) {
      case Segment::Line:
        pts.push_back(s.p[1]);
        break;
      case Segment::Quad:
      case Segment::Cubic: {
        // Wang's formula: n uniform steps keep the polyline within tol of a degree-d Bézier
        // curve when n ≥ sqrt(d(d-1)/8 · max_i |P_i − 2P_{i+1} + P_{i+2}| / tol).
        const int deg = s.kind == Segment::Quad ? 2 : 3;
        double m2 = 0;
        for (int i = 0; i + 2 <= deg; ++i)
          m2 = std::max(m2, (s.p[i] - 2 * s.p[i + 1] + s.p[i + 2]).norm());
        int n = 1;
        if (tol > 0 && m2 > 0)
          n = static_cast<int>(std::ceil(std::sqrt(deg * (deg - 1) / 8.0 * m2 / tol)));
        n = std::clamp(n, 1, 1 << 16);
        for (int k = 1; k < n; ++k) {
          const double t = static_cast<double>(k) / n, r = 1 - t;
          if (deg == 2)
            pts.push_back(r * r * s.p[0] + 2 * r * t * s.p[1] + t * t * s.p[2]);
          else
            pts.push_back(r * r * r * s.p[0] + 3 * r * r * t * s.p[1] + 3 * r * t * t * s.p[2] +
                          t * t * t * s.p[3]);
        }
        pts.push_back(s.end());
        break;
      }
      case Segment::Arc: {
        // The ellipse is the image of the unit circle under L = [u v]; a chord over an angle
        // step δ of the circle is within 1 − cos(δ/2) of it (the sagitta), so within
        // σ_max(L)·(1 − cos(δ/2)) of the ellipse.
        const double r = max_stretch(s.u.x(), s.u.y(), s.v.x(), s.v.y());
        double step = 2 * kPi;
        if (tol <= 0) {
          step = std::abs(s.dtheta);
        } else if (tol < r) {
          step = 2 * std::acos(1 - tol / r);
        }
        int n = step > 0 ? static_cast<int>(std::ceil(std::abs(s.dtheta) / step)) : 1;
        n = std::clamp(n, 1, 1 << 16);
        for (int k = 1; k < n; ++k) {
          const double t = s.theta1 + s.dtheta * k / n;
          pts.push_back(s.centre + std::cos(t) * s.u + std::sin(t) * s.v);
        }
        pts.push_back(s.p[1]);
        break;
      }
    }
  }
}

}  // namespace

std::string parse_svg_outline(std::string_view text, const std::string& name,
                              const std::string& path_id, double scale, ShapeFile& out) {
  out.loops.clear();
  out.fill_rule = FillRule::NonZero;
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed =
      doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed) {
    const std::ptrdiff_t off = std::clamp<std::ptrdiff_t>(parsed.offset, 0, text.size());
    const auto line = 1 + std::count(text.begin(), text.begin() + off, '\n');
    return name + ":" + std::to_string(line) + ": not valid XML (" + parsed.description() + ")";
  }
  const pugi::xml_node root = doc.document_element();
  if (local_name(root) != "svg")
    return name + ": not an SVG file (its root element is <" + printable(local_name(root), 40) +
           ">)";
  pugi::xml_node target;
  if (!path_id.empty()) {
    target = doc.find_node([&](const pugi::xml_node& n) {
      return n.type() == pugi::node_element && path_id == n.attribute("id").value();
    });
    if (!target) return name + " has no element with id " + quoted(printable(path_id));
    const std::string tn = local_name(target);
    if (!is_shape(tn) && tn != "g" && tn != "svg")
      return name + ": the element with id " + quoted(printable(path_id)) + " is a <" +
             printable(tn, 40) + ">, not a path, shape or group";
  }
  Reader reader(text, name);
  if (auto e = reader.visit(root, Affine{}, FillRule::NonZero, path_id.empty(), target, 0);
      !e.empty())
    return e;

  // The bounding box of every point and control point (an arc: its whole ellipse).
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  auto grow = [&](const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  bool any = false;
  for (const Element& e : reader.elements)
    for (const Subpath& sp : e.subpaths) {
      grow(sp.start);
      any = true;
      for (const Segment& s : sp.segments) {
        if (s.kind == Segment::Arc) {
          const Vec2 half(std::hypot(s.u.x(), s.v.x()), std::hypot(s.u.y(), s.v.y()));
          grow(s.centre - half);
          grow(s.centre + half);
        } else {
          for (int i = 0; i <= static_cast<int>(s.kind == Segment::Line   ? 1
                                                : s.kind == Segment::Quad ? 2
                                                                          : 3);
               ++i)
            grow(s.p[i]);
        }
      }
    }
  if (!any) return name + " has no closed path";
  const double diag = (hi - lo).norm();
  if (!std::isfinite(diag))
    return name + ": coordinates too large (not finite after the transforms)";
  const double tol = kSvgFlatteningTolerance * diag, eps = 1e-9 * diag;

  std::optional<FillRule> rule;
  std::size_t total = 0;
  std::vector<Vec2> pts;
  for (const Element& e : reader.elements) {
    bool kept = false;
    for (const Subpath& sp : e.subpaths) {
      const Vec2 last = sp.segments.empty() ? sp.start : sp.segments.back().end();
      if (!sp.closed && (last - sp.start).norm() > eps) continue;  // open: not an outline
      pts.clear();
      flatten(sp, tol, pts);
      Loop loop;
      for (const Vec2& p : pts)
        if (loop.empty() || (p - loop.back()).norm() > eps) loop.push_back(p);
      while (loop.size() > 1 && (loop.back() - loop.front()).norm() <= eps) loop.pop_back();
      if (loop.size() < 3) continue;  // draws nothing
      total += loop.size();
      if (total > kMaxPoints)
        return name + ": more than " + std::to_string(kMaxPoints) + " points once flattened";
      out.loops.push_back(std::move(loop));
      kept = true;
    }
    if (kept) {
      if (rule && *rule != e.rule)
        return name +
               ": its closed paths have different fill rules (nonzero and evenodd); "
               "give them one, or choose one with path_id";
      rule = e.rule;
    }
  }
  if (out.loops.empty()) return name + " has no closed path";
  out.fill_rule = *rule;
  // Metres, y up, the loops' bounding box centred on the origin.
  Vec2 mlo = Vec2::Constant(std::numeric_limits<double>::infinity()), mhi = -mlo;
  for (Loop& loop : out.loops)
    for (Vec2& p : loop) {
      p = Vec2(scale * p.x(), -scale * p.y());
      mlo = mlo.cwiseMin(p);
      mhi = mhi.cwiseMax(p);
    }
  const Vec2 centre = 0.5 * (mlo + mhi);
  for (Loop& loop : out.loops)
    for (Vec2& p : loop) p -= centre;
  return "";
}

}  // namespace invfree

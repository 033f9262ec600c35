// SVG outlines (scene_io/svg_outline.h): every path command, absolute and relative, implicit
// repeats and number forms; arcs and curves within the stated flattening tolerance (areas and
// the distance of the true curve from the polyline); transforms; fill rules; path_id; open
// paths; and the one-line errors.
#include "scene_io/svg_outline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace invfree {
namespace {

constexpr double kPi = std::numbers::pi;

std::string svg(const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\">\n" + body + "\n</svg>\n";
}
std::string path(const std::string& d) {
  return svg("<path d=\"" + d + "\"/>");
}

ShapeFile parse_ok(const std::string& text, double scale = 1.0, const std::string& id = "") {
  ShapeFile out;
  const std::string e = parse_svg_outline(text, "t.svg", id, scale, out);
  EXPECT_EQ(e, "") << text;
  return out;
}
std::string parse_error(const std::string& text, const std::string& id = "") {
  ShapeFile out;
  return parse_svg_outline(text, "t.svg", id, 1.0, out);
}

double signed_area(const Loop& l) {
  double a = 0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    const Vec2& p = l[i];
    const Vec2& q = l[(i + 1) % l.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}
double area(const ShapeFile& s) {
  double a = 0;
  for (const Loop& l : s.loops) a += std::abs(signed_area(l));
  return a;
}
double perimeter(const Loop& l) {
  double p = 0;
  for (std::size_t i = 0; i < l.size(); ++i) p += (l[(i + 1) % l.size()] - l[i]).norm();
  return p;
}
void expect_same_loops(const ShapeFile& a, const ShapeFile& b, double tol = 1e-9) {
  ASSERT_EQ(a.loops.size(), b.loops.size());
  for (std::size_t k = 0; k < a.loops.size(); ++k) {
    ASSERT_EQ(a.loops[k].size(), b.loops[k].size()) << "loop " << k;
    for (std::size_t i = 0; i < a.loops[k].size(); ++i)
      EXPECT_LE((a.loops[k][i] - b.loops[k][i]).norm(), tol) << "loop " << k << " point " << i;
  }
}
Vec2 bbox_size(const ShapeFile& s) {
  Vec2 lo = Vec2::Constant(1e300), hi = -lo;
  for (const Loop& l : s.loops)
    for (const Vec2& p : l) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  return hi - lo;
}
double distance_to_polyline(const Vec2& p, const Loop& l) {
  double best = 1e300;
  for (std::size_t i = 0; i < l.size(); ++i) {
    const Vec2 a = l[i], b = l[(i + 1) % l.size()];
    const double t =
        std::clamp((p - a).dot(b - a) / std::max(1e-300, (b - a).squaredNorm()), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - p).norm());
  }
  return best;
}

TEST(SvgOutline, SquareMappedToMetresYUpAndCentred) {
  const ShapeFile s = parse_ok(path("M0 0 L10 0 L0 10 Z"), 0.01);
  ASSERT_EQ(s.loops.size(), 1u);
  ASSERT_EQ(s.loops[0].size(), 3u);
  // (x, y) -> (0.01 x, -0.01 y), then the box [0, 0.1] x [-0.1, 0] centred.
  EXPECT_NEAR(s.loops[0][0].x(), -0.05, 1e-15);
  EXPECT_NEAR(s.loops[0][0].y(), 0.05, 1e-15);
  EXPECT_NEAR(s.loops[0][1].x(), 0.05, 1e-15);
  EXPECT_NEAR(s.loops[0][1].y(), 0.05, 1e-15);
  EXPECT_NEAR(s.loops[0][2].x(), -0.05, 1e-15);
  EXPECT_NEAR(s.loops[0][2].y(), -0.05, 1e-15);
  EXPECT_EQ(s.fill_rule, FillRule::NonZero);
}

TEST(SvgOutline, LineCommandsAbsoluteRelativeAndImplicit) {
  const ShapeFile ref = parse_ok(path("M 0 0 L 10 0 L 10 10 L 0 10 Z"));
  ASSERT_EQ(ref.loops.size(), 1u);
  EXPECT_EQ(ref.loops[0].size(), 4u);
  EXPECT_DOUBLE_EQ(area(ref), 100.0);
  for (const char* d :
       {"m0 0 l10 0 l0 10 l-10 0 z", "M0 0 H10 V10 H0 Z", "m0 0 h10 v10 h-10 z",
        "M0,0 10,0 10,10 0,10z", "m0 0 10 0 0 10 -10 0 Z", "M0 0 L10 0 10 10 0 10 0 0",
        "M0 0L1e1 0L10 1e+1L.0e1 10Z", "M+0-0L10,0,10,10,0,10Z", "M5 5 M0 0 h10 v10 h-10 z",
        "M0 0 L0 0 L10 0 L10 0 L10 10 L0 10 L0 10 Z"}) {
    SCOPED_TRACE(d);
    expect_same_loops(parse_ok(path(d)), ref);
  }
}

TEST(SvgOutline, NumbersRunTogether) {
  // "-.5.5" is -0.5 then 0.5; "1e-3" an exponent.
  expect_same_loops(parse_ok(path("M-.5.5L10-.5L10 10-.5 10Z")),
                    parse_ok(path("M -0.5 0.5 L 10 -0.5 L 10 10 L -0.5 10 Z")));
  expect_same_loops(parse_ok(path("M0 0h1e-3v1e-3h-1e-3z")),
                    parse_ok(path("M0 0 H0.001 V0.001 H0 Z")));
}

TEST(SvgOutline, QuadraticCurvesAndTheirShorthand) {
  // A parabolic segment: base 10, apex height 5 (control point at 10): area 2/3 · 10 · 5.
  const ShapeFile q = parse_ok(path("M0 0 Q5 10 10 0 Z"));
  const double tol = kSvgFlatteningTolerance * std::sqrt(200.0);
  EXPECT_NEAR(area(q), 100.0 / 3.0, tol * perimeter(q.loops[0]));
  EXPECT_LE(area(q), 100.0 / 3.0);  // the chords lie inside the convex curve
  expect_same_loops(q, parse_ok(path("m0 0 q5 10 10 0 z")));
  // T reflects the previous control point: (5,10) about (10,0) is (15,-10).
  const ShapeFile t = parse_ok(path("M0 0 Q5 10 10 0 T20 0 L20 20 L0 20 Z"));
  expect_same_loops(t, parse_ok(path("M0 0 Q5 10 10 0 Q15 -10 20 0 L20 20 L0 20 Z")));
  expect_same_loops(t, parse_ok(path("m0 0 q5 10 10 0 t10 0 l0 20 l-20 0 z")));
  // T after a non-quadratic command: the control point is the current point (a line).
  expect_same_loops(parse_ok(path("M0 0 L10 0 T10 10 L0 10 Z")),
                    parse_ok(path("M0 0 L10 0 Q10 0 10 10 L0 10 Z")));
}

TEST(SvgOutline, CubicCurvesAndTheirShorthand) {
  // Area under the cubic (0,0) (0,10) (10,10) (10,0): 3/20 · the control polygon's formula;
  // here the exact value from Green's theorem is 10·10·(3/5) = 60.
  const ShapeFile c = parse_ok(path("M0 0 C0 10 10 10 10 0 Z"));
  const double tol = kSvgFlatteningTolerance * std::sqrt(200.0);
  EXPECT_NEAR(area(c), 60.0, tol * perimeter(c.loops[0]));
  expect_same_loops(c, parse_ok(path("m0 0 c0 10 10 10 10 0 z")));
  // S reflects the previous second control point: (10,10) about (10,0) is (10,-10).
  const ShapeFile s = parse_ok(path("M0 0 C0 10 10 10 10 0 S20 -10 20 0 L20 20 L0 20 Z"));
  expect_same_loops(s, parse_ok(path("M0 0 C0 10 10 10 10 0 C10 -10 20 -10 20 0 L20 20 L0 20 Z")));
  expect_same_loops(s, parse_ok(path("m0 0 c0 10 10 10 10 0 s10 -10 10 0 l0 20 l-20 0 z")));
  // S after a non-cubic command: the first control point is the current point.
  expect_same_loops(parse_ok(path("M0 0 L0 1 S10 10 10 0 Z")),
                    parse_ok(path("M0 0 L0 1 C0 1 10 10 10 0 Z")));
}

// Wang's bound: the true curve lies within the stated tolerance of the polyline.
TEST(SvgOutline, CubicFlattenedWithinTheStatedTolerance) {
  const Vec2 p[4] = {{0, 0}, {0, 100}, {100, 100}, {100, -40}};
  const ShapeFile s = parse_ok(path("M0 0 C0 100 100 100 100 -40 Z"));
  ASSERT_EQ(s.loops.size(), 1u);
  const Loop& l = s.loops[0];
  // Back to SVG units: loop[0] is the start (0, 0), y flipped.
  const Vec2 o = l[0];
  Loop svg_loop;
  for (const Vec2& q : l) svg_loop.emplace_back(q.x() - o.x(), -(q.y() - o.y()));
  const double tol = kSvgFlatteningTolerance * std::hypot(100.0, 140.0);
  double worst = 0;
  for (int k = 0; k <= 20000; ++k) {
    const double t = k / 20000.0, r = 1 - t;
    const Vec2 c =
        r * r * r * p[0] + 3 * r * r * t * p[1] + 3 * r * t * t * p[2] + t * t * t * p[3];
    worst = std::max(worst, distance_to_polyline(c, svg_loop));
  }
  EXPECT_LE(worst, tol);
  EXPECT_GT(worst, tol / 20);  // and not needlessly fine
}

TEST(SvgOutline, CircleByTwoArcsHasAreaPiRSquaredWithinTheBound) {
  const double r = 10;
  for (const char* d : {"M 60 50 A 10 10 0 0 1 40 50 A 10 10 0 0 1 60 50 Z",
                        "M 60 50 a 10 10 0 0 0 -20 0 a 10 10 0 0 0 20 0 z",
                        "M60,50A10,10,0,1,1,40,50A10,10,0,1,1,60,50Z",
                        "M60 50A10 10 0 0140 50A10 10 0 0160 50Z"}) {  // flags run together
    SCOPED_TRACE(d);
    const ShapeFile s = parse_ok(path(d), 0.01);
    ASSERT_EQ(s.loops.size(), 1u);
    const double tol_m = kSvgFlatteningTolerance * std::hypot(2 * r, 2 * r) * 0.01;
    const double exact = kPi * (r * 0.01) * (r * 0.01);
    EXPECT_LE(area(s), exact);
    EXPECT_NEAR(area(s), exact, 2 * kPi * r * 0.01 * tol_m);
    // Every chord's sagitta within the tolerance; every point on the circle.
    const Loop& l = s.loops[0];
    for (std::size_t i = 0; i < l.size(); ++i) {
      EXPECT_NEAR(l[i].norm(), r * 0.01, 1e-12);
      const Vec2 mid = 0.5 * (l[i] + l[(i + 1) % l.size()]);
      EXPECT_LE(r * 0.01 - mid.norm(), tol_m);
    }
  }
}

TEST(SvgOutline, ArcFlagsChooseTheFourArcs) {
  // From (10,0) to (0,10) with radius 10: centres (0,0) or (10,10).
  const double q = 25 * kPi;  // a quarter disk
  auto a = [&](const char* flags) {
    return area(parse_ok(path(std::string("M10 0 A10 10 0 ") + flags + " 0 10 L0 0 Z")));
  };
  // The drawing's box holds the whole circle: at most [0,20]², D = 20√2.
  const double tol_area = kSvgFlatteningTolerance * 20 * std::sqrt(2.0) * 2 * kPi * 10;
  EXPECT_NEAR(a("1 1"), 3 * q + 100, tol_area);
  EXPECT_NEAR(a("1 0"), 3 * q, tol_area);
  EXPECT_NEAR(a("0 1"), q, tol_area);
  EXPECT_NEAR(a("0 0"), 100 - q, tol_area);
}

TEST(SvgOutline, ArcRadiiTooSmallAreScaledUpAndZeroRadiusIsALine) {
  // F.6.6: radius 1 between points 10 apart becomes 5: a half disk.
  // The drawing's box is the whole circle's, [0,10] x [-5,5]; the arc is 5π long.
  EXPECT_NEAR(area(parse_ok(path("M0 0 A1 1 0 0 1 10 0 Z"))), 12.5 * kPi,
              kSvgFlatteningTolerance * std::sqrt(200.0) * 5 * kPi);
  expect_same_loops(parse_ok(path("M0 0 A0 5 0 0 1 10 0 L10 10 Z")),
                    parse_ok(path("M0 0 L10 0 L10 10 Z")));
}

TEST(SvgOutline, RotatedEllipticalArcWithinTheTolerance) {
  // A full ellipse rx 20, ry 5, rotated 30°, centred at the origin, from two arcs.
  const double c = std::cos(kPi / 6), s = std::sin(kPi / 6);
  const Vec2 p0(20 * c, 20 * s), p1(-20 * c, -20 * s);
  char d[256];  // (snprintf, not a chain of "..." + std::string: GCC 12 warns falsely on it)
  std::snprintf(d, sizeof d, "M%.17g %.17g A20 5 30 0 1 %.17g %.17g A20 5 30 0 1 %.17g %.17gZ",
                p0.x(), p0.y(), p1.x(), p1.y(), p0.x(), p0.y());
  const ShapeFile out = parse_ok(path(d));
  ASSERT_EQ(out.loops.size(), 1u);
  // The drawing's box is the ellipse's: the centred loop is the ellipse about the origin.
  const double half_w = std::hypot(20 * c, 5 * s), half_h = std::hypot(20 * s, 5 * c);
  const double tol = kSvgFlatteningTolerance * 2 * std::hypot(half_w, half_h);
  EXPECT_LE(area(out), kPi * 100);
  EXPECT_NEAR(area(out), kPi * 100, tol * perimeter(out.loops[0]));
  double worst = 0;
  for (int k = 0; k < 20000; ++k) {
    const double t = 2 * kPi * k / 20000;
    const Vec2 e(20 * std::cos(t) * c - 5 * std::sin(t) * s,
                 -(20 * std::cos(t) * s + 5 * std::sin(t) * c));
    worst = std::max(worst, distance_to_polyline(e, out.loops[0]));
  }
  EXPECT_LE(worst, tol + 1e-5);  // 1e-5: the path data's 6 decimals
}

TEST(SvgOutline, PolygonRectCircleEllipse) {
  EXPECT_DOUBLE_EQ(area(parse_ok(svg("<polygon points=\"0,0 10,0 10,5 0,5\"/>"))), 50.0);
  EXPECT_DOUBLE_EQ(area(parse_ok(svg("<rect x=\"1\" y=\"2\" width=\"10\" height=\"5px\"/>"))),
                   50.0);
  // Areas within the tolerance (D: the box's diagonal) times the curves' length.
  const double eps = kSvgFlatteningTolerance;
  const double rounded = area(parse_ok(svg("<rect width=\"10\" height=\"6\" rx=\"2\"/>")));
  EXPECT_NEAR(rounded, 60 - (4 - kPi) * 4, eps * std::hypot(10, 6) * 4 * kPi);  // 4 quarter disks
  EXPECT_NEAR(area(parse_ok(svg("<circle cx=\"5\" cy=\"5\" r=\"10\"/>"))), 100 * kPi,
              eps * std::hypot(20, 20) * 20 * kPi);
  EXPECT_NEAR(area(parse_ok(svg("<ellipse cx=\"5\" cy=\"5\" rx=\"10\" ry=\"4\"/>"))), 40 * kPi,
              eps * std::hypot(20, 8) * 2 * kPi * 10);
  // Not drawn: zero size; a polyline is open unless it ends where it began.
  EXPECT_EQ(parse_error(svg("<rect width=\"0\" height=\"5\"/><polyline points=\"0 0 1 0 1 1\"/>")),
            "t.svg has no closed path");
  EXPECT_DOUBLE_EQ(area(parse_ok(svg("<polyline points=\"0 0 4 0 4 4 0 0\"/>"))), 8.0);
}

TEST(SvgOutline, TransformsOfElementsAndGroupsCompose) {
  // rotate(90) makes 10 x 5 into 5 x 10; the group's scale(2) into 10 x 20.
  const ShapeFile r = parse_ok(svg(
      "<g transform=\"scale(2)\"><rect width=\"10\" height=\"5\" transform=\"rotate(90)\"/></g>"));
  EXPECT_NEAR(bbox_size(r).x(), 10, 1e-12);
  EXPECT_NEAR(bbox_size(r).y(), 20, 1e-12);
  EXPECT_NEAR(area(r), 200, 1e-9);
  // translate: two squares 20 apart.
  const ShapeFile t =
      parse_ok(svg("<rect width=\"10\" height=\"10\"/>"
                   "<g transform=\"translate(20)\"><rect width=\"10\" height=\"10\"/></g>"));
  EXPECT_NEAR(bbox_size(t).x(), 30, 1e-12);
  EXPECT_NEAR(bbox_size(t).y(), 10, 1e-12);
  // skewX(45): a parallelogram of the same area, twice as wide.
  const ShapeFile k = parse_ok(svg("<rect width=\"10\" height=\"10\" transform=\"skewX(45)\"/>"));
  EXPECT_NEAR(area(k), 100, 1e-9);
  EXPECT_NEAR(bbox_size(k).x(), 20, 1e-9);
  const ShapeFile ky = parse_ok(svg("<rect width=\"10\" height=\"10\" transform=\"skewY(45)\"/>"));
  EXPECT_NEAR(bbox_size(ky).y(), 20, 1e-9);
  // matrix(a b c d e f) and a list applied right to left: translate then scale of the point.
  const ShapeFile m =
      parse_ok(svg("<rect width=\"10\" height=\"10\"/>"
                   "<rect width=\"10\" height=\"10\" "
                   "transform=\"matrix(2 0 0 3 0 0), translate(10,0)\"/>"));
  EXPECT_NEAR(bbox_size(m).x(), 40, 1e-12);  // the second spans x in [20, 40]
  EXPECT_NEAR(bbox_size(m).y(), 30, 1e-12);
  // rotate about a centre: rotate(180 5 5) maps [0,10]² onto itself.
  expect_same_loops(
      parse_ok(svg("<rect width=\"10\" height=\"10\" transform=\"rotate(180 5 5)\"/>"
                   "<rect x=\"20\" width=\"1\" height=\"1\"/>")),
      parse_ok(svg("<path d=\"M10 10 H0 V0 H10 Z\"/><rect x=\"20\" width=\"1\" height=\"1\"/>")));
}

TEST(SvgOutline, FillRuleFromAttributeStyleAndGroups) {
  const std::string hole = "d=\"M0 0 H10 V10 H0 Z M2 2 H8 V8 H2 Z\"";
  EXPECT_EQ(parse_ok(svg("<path " + hole + "/>")).fill_rule, FillRule::NonZero);
  EXPECT_EQ(parse_ok(svg("<path fill-rule=\"evenodd\" " + hole + "/>")).fill_rule,
            FillRule::EvenOdd);
  EXPECT_EQ(
      parse_ok(svg("<path style=\"fill:#000; fill-rule : evenodd\" " + hole + "/>")).fill_rule,
      FillRule::EvenOdd);
  EXPECT_EQ(
      parse_ok(svg("<g style=\"fill-rule:evenodd\"><g><path " + hole + "/></g></g>")).fill_rule,
      FillRule::EvenOdd);
  EXPECT_EQ(parse_ok(svg("<g fill-rule=\"evenodd\"><path fill-rule=\"nonzero\" " + hole + "/></g>"))
                .fill_rule,
            FillRule::NonZero);
  EXPECT_EQ(parse_ok(svg("<path fill-rule=\"evenodd\" " + hole + "/>")).loops.size(), 2u);
  EXPECT_NE(parse_error(svg("<path fill-rule=\"evenodd\" " + hole + "/><path " + hole + "/>"))
                .find("different fill rules"),
            std::string::npos);
  EXPECT_NE(parse_error(svg("<path fill-rule=\"odd\" " + hole + "/>")).find("fill-rule: expected"),
            std::string::npos);
}

TEST(SvgOutline, PathIdSelectsOneElementOrGroup) {
  const std::string text =
      svg("<defs><path id=\"hidden\" d=\"M0 0 H1 V1 Z\"/></defs>"
          "<g id=\"both\" transform=\"scale(2)\"><path id=\"a\" d=\"M0 0 H10 V10 H0 Z\"/>"
          "<path id=\"b\" d=\"M20 0 H25 V5 H20 Z\"/></g><text id=\"words\">hi</text>");
  EXPECT_EQ(parse_ok(text).loops.size(), 2u);  // <defs> is not drawn
  EXPECT_NEAR(area(parse_ok(text, 1.0, "a")), 400, 1e-9);
  EXPECT_NEAR(area(parse_ok(text, 1.0, "b")), 100, 1e-9);
  EXPECT_EQ(parse_ok(text, 1.0, "both").loops.size(), 2u);
  EXPECT_NEAR(area(parse_ok(text, 1.0, "hidden")), 0.5, 1e-12);
  EXPECT_EQ(parse_error(text, "c"), "t.svg has no element with id \"c\"");
  EXPECT_NE(parse_error(text, "words").find("is a <text>"), std::string::npos);
}

TEST(SvgOutline, OpenSubpathsIgnored) {
  const ShapeFile s =
      parse_ok(path("M0 0 L10 0 L10 10 M20 0 L30 0 L30 10 Z M40 0 L50 0 L50 10 L40 0"));
  ASSERT_EQ(s.loops.size(), 2u);  // the Z one and the one ending where it began
  EXPECT_EQ(s.loops[0].size(), 3u);
  EXPECT_EQ(s.loops[1].size(), 3u);
  EXPECT_EQ(parse_error(path("M0 0 L10 0 L10 10")), "t.svg has no closed path");
  EXPECT_EQ(parse_error(svg("")), "t.svg has no closed path");
  // A command after Z starts a new subpath at the old start.
  EXPECT_EQ(parse_ok(path("M0 0 H10 V10 Z L-10 0 L-10 -10 Z")).loops.size(), 2u);
}

TEST(SvgOutline, MalformedFilesAreOneLineErrors) {
  EXPECT_EQ(parse_error("<svg><path d=\"M0 0\"></svg>").rfind("t.svg:1: not valid XML (", 0), 0u);
  EXPECT_EQ(parse_error("<html/>"), "t.svg: not an SVG file (its root element is <html>)");
  EXPECT_EQ(parse_error(svg("<path id=\"p\" d=\"M0 0 L10 x\"/>")),
            "t.svg:2: <path id=\"p\">: d: expected a number after 'L', got 'x' at character 10");
  EXPECT_EQ(parse_error(path("L0 0")),
            "t.svg:2: <path>: d: path data must begin with M or m at character 1");
  EXPECT_NE(parse_error(path("M0 0 A1 1 0 2 1 3 3")).find("arc flag"), std::string::npos);
  EXPECT_NE(parse_error(path("M0 0 Z 1 2")).find("expected a command after 'Z', got '1 2'"),
            std::string::npos);
  EXPECT_NE(parse_error(svg("<polygon points=\"0 0 1 0 1\"/>"))
                .find("points: 5 numbers, expected x,y pairs"),
            std::string::npos);
  EXPECT_NE(parse_error(svg("<rect width=\"1\" height=\"1\" transform=\"spin(3)\"/>"))
                .find("transform: unknown transform 'spin'"),
            std::string::npos);
  EXPECT_NE(parse_error(svg("<rect width=\"1\" height=\"1\" transform=\"scale(1 2 3)\"/>"))
                .find("wrong number of values"),
            std::string::npos);
  EXPECT_NE(parse_error(svg("<rect width=\"1em\" height=\"1\"/>")).find("width: expected a number"),
            std::string::npos);
  EXPECT_NE(parse_error(svg("<g transform=\"scale(1e300)\"><g transform=\"scale(1e300)\">"
                            "<rect width=\"1\" height=\"1\"/></g></g>"))
                .find("not finite"),
            std::string::npos);
  for (const std::string& e :
       {parse_error("<svg><path d=\"M0 0\"></svg>"), parse_error(path("Mx"))})
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

}  // namespace
}  // namespace invfree

// Loop validation (polygon_checks.h): the basic checks per loop, then one quadtree pass
// over every edge of every loop that finds the first touching or crossing pair inside a loop
// and the first between two loops, each decided by the exact orientation predicate.
#include "shape/polygon_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>

#include "collision/orientation.h"
#include "shape/triangulate.h"

namespace invfree {
namespace {

// Beyond this the exact predicate's products could overflow (collision/orientation.h
// holds to about 1e145); no body is that large.
constexpr double kMaxCoordinate = 1e100;

// How two closed segments meet: not at all, properly (each crosses the other's line at
// an interior point), or in any other way (an end point on the other, collinear overlap).
enum class Contact { None, Cross, Touch };

// p lies on the closed segment [a, b], given that a, b, p are collinear (exact compares).
bool within_box(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

Contact segment_contact(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return Contact::Cross;
  if ((o1 == 0 && within_box(a, b, c)) || (o2 == 0 && within_box(a, b, d)) ||
      (o3 == 0 && within_box(c, d, a)) || (o4 == 0 && within_box(c, d, b)))
    return Contact::Touch;
  return Contact::None;
}

// Consecutive edges p->q and q->r meet at q; they overlap beyond it only when r folds back
// along p->q (collinear, p and r on the same side of q).
bool folds_back(const Vec2& p, const Vec2& q, const Vec2& r) {
  if (orientation(p, q, r) != 0) return false;
  if (p.x() != q.x()) return (p.x() < q.x()) == (r.x() < q.x()) && r.x() != q.x();
  return (p.y() < q.y()) == (r.y() < q.y()) && r.y() != q.y();
}

struct Seg {
  int loop, edge;
  Vec2 a, b;
};

// The first pair found by the quadtree pass, ordered by (loop a, loop b, edge a, edge b).
struct PairHit {
  int loop_a = -1, loop_b = -1, edge_a = -1, edge_b = -1;
  Contact contact = Contact::None;
  bool found() const { return loop_a >= 0; }
  void offer(int la, int ea, int lb, int eb, Contact c) {
    if (std::tie(la, lb, ea, eb) > std::tie(lb, la, eb, ea)) {
      std::swap(la, lb);
      std::swap(ea, eb);
    }
    if (found() && std::tie(loop_a, loop_b, edge_a, edge_b) <= std::tie(la, lb, ea, eb)) return;
    loop_a = la, loop_b = lb, edge_a = ea, edge_b = eb, contact = c;
  }
};

struct GridResult {
  PairHit within;   // two edges of one loop (not consecutive ones meeting at their point)
  PairHit between;  // edges of two loops
};

bool adjacent(int i, int j, int n) {
  return j == i + 1 || i == j + 1 || (i == 0 && j == n - 1) || (j == 0 && i == n - 1);
}

// Conservatively, whether segment s meets the closed box: their boxes overlap and the
// box's corners are not all clearly on one side of the segment's line (floating point
// with a generous tolerance; a false "meets" only costs a test).
bool meets_box(const Seg& s, const Eigen::AlignedBox2d& box) {
  if (std::max(s.a.x(), s.b.x()) < box.min().x() || std::min(s.a.x(), s.b.x()) > box.max().x() ||
      std::max(s.a.y(), s.b.y()) < box.min().y() || std::min(s.a.y(), s.b.y()) > box.max().y())
    return false;
  const Vec2 d = s.b - s.a;
  int above = 0, below = 0;
  for (const Vec2& c : {box.min(), box.max(), Vec2(box.min().x(), box.max().y()),
                        Vec2(box.max().x(), box.min().y())}) {
    const Vec2 e = c - s.a;
    const double cross = d.x() * e.y() - d.y() * e.x();
    const double tol = 1e-9 * d.cwiseAbs().maxCoeff() * e.cwiseAbs().maxCoeff();
    if (cross > tol)
      ++above;
    else if (cross < -tol)
      ++below;
    else
      return true;
  }
  return above > 0 && below > 0;
}

// Leaves of at most kLeafSize segments, or at most kMaxDepth halvings of the root box.
constexpr std::size_t kLeafSize = 24;
constexpr int kMaxDepth = 24;

struct ContactSearch {
  std::span<const Loop> loops;
  std::vector<char> within;  // per loop: test its own edges against each other
  std::vector<Seg> segs;
  GridResult result;

  // Whether a box's segments hold any pair to test: two loops, or a loop tested within.
  bool anything_to_test(const std::vector<int>& ids) const {
    for (std::size_t i = 1; i < ids.size(); ++i)
      if (segs[ids[i]].loop != segs[ids[0]].loop) return true;
    return ids.size() > 1 && within[segs[ids[0]].loop];
  }

  void test_pair(const Seg& s, const Seg& t) {
    if (s.loop == t.loop && !within[s.loop]) return;
    if (std::max(std::min(s.a.x(), s.b.x()), std::min(t.a.x(), t.b.x())) >
            std::min(std::max(s.a.x(), s.b.x()), std::max(t.a.x(), t.b.x())) ||
        std::max(std::min(s.a.y(), s.b.y()), std::min(t.a.y(), t.b.y())) >
            std::min(std::max(s.a.y(), s.b.y()), std::max(t.a.y(), t.b.y())))
      return;
    if (s.loop == t.loop) {
      const int n = static_cast<int>(loops[s.loop].size());
      if (adjacent(s.edge, t.edge, n)) return;  // checked by folds_back
      const Contact c = segment_contact(s.a, s.b, t.a, t.b);
      if (c != Contact::None) result.within.offer(s.loop, s.edge, t.loop, t.edge, c);
    } else {
      const Contact c = segment_contact(s.a, s.b, t.a, t.b);
      if (c != Contact::None) result.between.offer(s.loop, s.edge, t.loop, t.edge, c);
    }
  }

  // A quadtree built on the fly: a box with many segments is split in four, each segment
  // going to every quarter it meets; the pairs of a leaf are tested. Segments crowding
  // one spot (a star's centre) get small boxes there, so the work stays near
  // O(n log n) where a uniform grid would be O(n^2).
  void search(const Eigen::AlignedBox2d& box, const std::vector<int>& ids, int depth) {
    if (!anything_to_test(ids)) return;
    if (ids.size() <= kLeafSize || depth >= kMaxDepth) {
      for (std::size_t i = 0; i < ids.size(); ++i)
        for (std::size_t j = i + 1; j < ids.size(); ++j) test_pair(segs[ids[i]], segs[ids[j]]);
      return;
    }
    const Vec2 mid = box.min() / 2 + box.max() / 2;
    const Eigen::AlignedBox2d quarters[4] = {
        {box.min(), mid},
        {Vec2(mid.x(), box.min().y()), Vec2(box.max().x(), mid.y())},
        {Vec2(box.min().x(), mid.y()), Vec2(mid.x(), box.max().y())},
        {mid, box.max()}};
    std::vector<int> sub[4];
    for (int id : ids)
      for (int q = 0; q < 4; ++q)
        if (meets_box(segs[id], quarters[q])) sub[q].push_back(id);
    // Splitting that does not separate anything (every segment through the centre) would
    // only repeat the pairs: test them here instead.
    bool separates = false;
    for (const auto& s : sub) separates = separates || s.size() < ids.size();
    if (!separates) {
      search(box, ids, kMaxDepth);
      return;
    }
    for (int q = 0; q < 4; ++q)
      if (sub[q].size() > 1) search(quarters[q], sub[q], depth + 1);
  }
};

// Every pair of segments that share a quadtree leaf, decided exactly: pairs of two loops,
// and pairs of one loop where `within` says so. Loops must have passed the basic checks
// (finite, >= 3 points, no repeated consecutive point).
GridResult find_contacts(std::span<const Loop> loops, std::vector<char> within) {
  ContactSearch search{loops, std::move(within), {}, {}};
  Eigen::AlignedBox2d box;
  for (int l = 0; l < static_cast<int>(loops.size()); ++l) {
    const Loop& loop = loops[l];
    const int n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i) {
      search.segs.push_back({l, i, loop[i], loop[(i + 1) % n]});
      box.extend(loop[i]);
    }
  }
  std::vector<int> ids(search.segs.size());
  std::iota(ids.begin(), ids.end(), 0);
  search.search(box, ids, 0);
  return search.result;
}

// Everything about one loop that needs no other edge: count, finite, repeated points,
// collinear, folds back.
std::string basic_checks(const Loop& loop, const std::string& name) {
  const int n = static_cast<int>(loop.size());
  if (n < 3) return name + ": fewer than three points";
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(loop[i].x()) || !std::isfinite(loop[i].y()))
      return name + ": point " + std::to_string(i) + " is not finite";
  for (int i = 0; i < n; ++i)
    if (std::abs(loop[i].x()) > kMaxCoordinate || std::abs(loop[i].y()) > kMaxCoordinate)
      return name + ": point " + std::to_string(i) + " is out of range (|coordinate| > 1e100 m)";
  for (int i = 0; i < n; ++i)
    if (loop[i] == loop[(i + 1) % n])
      return name + ": points " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
             " coincide";
  bool any_turn = false;
  for (int i = 2; i < n && !any_turn; ++i) any_turn = orientation(loop[0], loop[1], loop[i]) != 0;
  if (!any_turn) return name + ": zero area";
  for (int i = 0; i < n; ++i)
    if (folds_back(loop[i], loop[(i + 1) % n], loop[(i + 2) % n]))
      return name + ": edges " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
             " overlap (the loop doubles back)";
  return "";
}

std::string within_reason(const PairHit& hit, const std::string& name) {
  return name + ": edges " + std::to_string(hit.edge_a) + " and " + std::to_string(hit.edge_b) +
         (hit.contact == Contact::Cross ? " cross" : " touch") + " (self-intersecting)";
}

// Basic checks of each loop in order, then the quadtree pass; "" with the contacts when fine.
std::string check_all(std::span<const Loop> loops, std::span<const std::string> names,
                      GridResult& contacts) {
  for (std::size_t k = 0; k < loops.size(); ++k)
    if (std::string r = basic_checks(loops[k], names[k]); !r.empty()) return r;
  // A loop CGAL's sweep finds simple needs no pair search of its own: the search, which
  // can approach O(n^2) for a fan of long edges (a star), then only runs where two loops
  // share a box, or to name the pair of a loop that is not simple.
  std::vector<char> within(loops.size(), 1);
  for (std::size_t k = 0; k < loops.size(); ++k)
    within[k] = !loop_is_simple(loops[k]).value_or(false);
  contacts = find_contacts(loops, std::move(within));
  if (contacts.within.found()) return within_reason(contacts.within, names[contacts.within.loop_a]);
  return "";
}

Eigen::AlignedBox2d loop_box(const Loop& loop) {
  Eigen::AlignedBox2d box;
  for (const Vec2& p : loop) box.extend(p);
  return box;
}

}  // namespace

double loop_signed_area(const Loop& loop) {
  if (loop.size() < 3) return 0.0;
  double twice = 0.0;
  const Vec2& o = loop[0];
  for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
    const Vec2 u = loop[i] - o, v = loop[i + 1] - o;
    twice += u.x() * v.y() - u.y() * v.x();
  }
  return 0.5 * twice;
}

int point_in_loop(const Vec2& p, const Loop& loop) {
  const std::size_t n = loop.size();
  int w = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = loop[i], &b = loop[(i + 1) % n];
    const int o = orientation(a, b, p);
    if (o == 0 && within_box(a, b, p)) return 0;
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && o > 0) ++w;
    } else if (b.y() <= p.y() && o < 0) {
      --w;
    }
  }
  return w != 0 ? 1 : -1;
}

int winding_number(const Vec2& p, const Loop& loop) {
  const std::size_t n = loop.size();
  int w = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = loop[i], &b = loop[(i + 1) % n];
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && orientation(a, b, p) > 0) ++w;
    } else if (b.y() <= p.y() && orientation(a, b, p) < 0) {
      --w;
    }
  }
  return w;
}

std::string check_loop(const Loop& loop, const std::string& name) {
  GridResult contacts;
  return check_all(std::span<const Loop>(&loop, 1), std::span<const std::string>(&name, 1),
                   contacts);
}

std::string check_disjoint_loops(std::span<const Loop> loops, std::span<const std::string> names) {
  GridResult contacts;
  if (std::string r = check_all(loops, names, contacts); !r.empty()) return r;
  if (contacts.between.found())
    return names[contacts.between.loop_a] + " and " + names[contacts.between.loop_b] +
           (contacts.between.contact == Contact::Cross ? " cross" : " touch");
  return "";
}

std::string check_polygon_with_holes(const Loop& outline, std::span<const Loop> holes) {
  std::vector<Loop> loops{outline};
  std::vector<std::string> names{"outline"};
  for (std::size_t k = 0; k < holes.size(); ++k) {
    loops.push_back(holes[k]);
    names.push_back("holes[" + std::to_string(k) + "]");
  }
  GridResult contacts;
  if (std::string r = check_all(loops, names, contacts); !r.empty()) return r;
  if (const PairHit& hit = contacts.between; hit.found()) {
    if (hit.loop_a == 0)
      return names[hit.loop_b] +
             (hit.contact == Contact::Cross ? ": crosses the outline" : ": touches the outline");
    return names[hit.loop_a] + " and " + names[hit.loop_b] +
           (hit.contact == Contact::Cross ? " overlap" : " touch");
  }
  // Disjoint closed curves: one point of a hole tells on which side of another it lies.
  for (std::size_t k = 0; k < holes.size(); ++k)
    if (point_in_loop(holes[k][0], outline) < 0) return names[k + 1] + ": not inside the outline";
  std::vector<Eigen::AlignedBox2d> boxes;
  for (const Loop& hole : holes) boxes.push_back(loop_box(hole));
  for (std::size_t a = 0; a < holes.size(); ++a)
    for (std::size_t b = 0; b < holes.size(); ++b)
      if (a != b && boxes[a].contains(holes[b][0]) && point_in_loop(holes[b][0], holes[a]) > 0)
        return names[std::min(a, b) + 1] + " and " + names[std::max(a, b) + 1] + " overlap";
  return "";
}

}  // namespace invfree

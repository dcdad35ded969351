#include "dataset/geometry/polygon_2d.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <stdexcept>
#include <utility>

namespace lc2wf {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Points of all tiles, near-equal ones shared (tiles are small: a linear scan is enough).
class PointSet {
 public:
  explicit PointSet(double tol) : tol2_(tol * tol) {}
  int id(const Vec2& p) {
    for (size_t i = 0; i < points_.size(); ++i)
      if ((points_[i] - p).squaredNorm() <= tol2_) return static_cast<int>(i);
    points_.push_back(p);
    return static_cast<int>(points_.size()) - 1;
  }
  const std::vector<Vec2>& points() const { return points_; }

 private:
  double tol2_;
  std::vector<Vec2> points_;
};

// Clockwise turn from the way back (cur -> prev) to a candidate (cur -> next), in [0, 2 pi): the smallest
// keeps a loop on its own region where two regions touch at a point.
double clockwise_turn(const Vec2& back, const Vec2& next) {
  double ccw = std::atan2(cross(back, next), back.dot(next));
  if (ccw <= 0) ccw += 2 * M_PI;
  return 2 * M_PI - ccw;
}

}  // namespace

double signed_area(const Polygon2& p) {
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

Polygon2 clip_half_plane(const Polygon2& p, double a, double b, double c, double tol) {
  Polygon2 out;
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& cur = p[i];
    const Vec2& nxt = p[(i + 1) % n];
    const double dc = a * cur.x() + b * cur.y() + c, dn = a * nxt.x() + b * nxt.y() + c;
    if (dc >= -tol) out.push_back(cur);
    if ((dc > tol && dn < -tol) || (dc < -tol && dn > tol)) out.push_back(cur + (nxt - cur) * (dc / (dc - dn)));
  }
  Polygon2 clean;
  for (const Vec2& q : out)
    if (clean.empty() || (q - clean.back()).norm() > tol) clean.push_back(q);
  while (clean.size() > 1 && (clean.front() - clean.back()).norm() <= tol) clean.pop_back();
  if (clean.size() < 3) clean.clear();
  return clean;
}

std::vector<Polygon2> subtract_convex(const Polygon2& p, const Polygon2& cut, double min_area) {
  if (p.empty()) return {};
  if (cut.size() < 3 || std::abs(signed_area(cut)) <= min_area) return {p};
  Eigen::AlignedBox2d pb, cb;
  for (const Vec2& v : p) pb.extend(v);
  for (const Vec2& v : cut) cb.extend(v);
  if (!pb.intersects(cb)) return {p};
  std::vector<Polygon2> pieces;
  Polygon2 rest = p;
  for (size_t i = 0; i < cut.size() && !rest.empty(); ++i) {
    const Vec2 u = cut[i], d = cut[(i + 1) % cut.size()] - u;
    const double len = d.norm();
    if (len <= 0) continue;
    const Vec2 n(-d.y() / len, d.x() / len);  // points into the cut (counter-clockwise)
    const double c = -n.dot(u);
    Polygon2 outside = clip_half_plane(rest, -n.x(), -n.y(), -c);
    if (!outside.empty() && signed_area(outside) > min_area) pieces.push_back(std::move(outside));
    rest = clip_half_plane(rest, n.x(), n.y(), c);
  }
  return pieces;  // what is left in `rest` lies inside the cut
}

namespace {

using DirectedEdges = std::map<std::pair<int, int>, int>;  // (from, to) -> how many times

// The union's boundary as directed edges between shared points: tile edges split where another tile's
// corner lies on them; a stretch walked both ways is inside and cancels.
DirectedEdges outline_edges(const std::vector<Polygon2>& tiles, PointSet& set, double tol) {
  std::vector<std::vector<int>> loops_in;
  for (const Polygon2& t : tiles) {
    std::vector<int> ids;
    for (const Vec2& v : t) {
      const int id = set.id(v);
      if (ids.empty() || ids.back() != id) ids.push_back(id);
    }
    while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back();
    if (ids.size() >= 3) loops_in.push_back(std::move(ids));
  }
  const std::vector<Vec2>& pts = set.points();
  DirectedEdges count;
  for (const auto& ids : loops_in) {
    for (size_t k = 0; k < ids.size(); ++k) {
      const int i = ids[k], j = ids[(k + 1) % ids.size()];
      const Vec2 d = pts[j] - pts[i];
      const double len2 = d.squaredNorm();
      std::vector<std::pair<double, int>> inner;
      for (size_t q = 0; q < pts.size(); ++q) {
        if (static_cast<int>(q) == i || static_cast<int>(q) == j) continue;
        const double t = (pts[q] - pts[i]).dot(d) / len2;
        if (t <= 0 || t >= 1) continue;
        if (std::abs(cross(d, pts[q] - pts[i])) / std::sqrt(len2) <= tol) inner.emplace_back(t, static_cast<int>(q));
      }
      std::sort(inner.begin(), inner.end());
      int from = i;
      inner.emplace_back(1.0, j);
      for (const auto& [t, to] : inner) {
        if (auto back = count.find({to, from}); back != count.end() && back->second > 0) {
          --back->second;
        } else {
          ++count[{from, to}];
        }
        from = to;
      }
    }
  }
  return count;
}

// Closed loops of directed edges; at a point with several ways on, the smallest clockwise turn keeps each
// loop on its own region (the faces of a plane graph).
std::vector<std::vector<int>> trace_loops(const std::vector<Vec2>& pts, const DirectedEdges& count) {
  std::map<int, std::vector<int>> out_edges;
  int remaining = 0;
  for (const auto& [e, n] : count)
    for (int k = 0; k < n; ++k) {
      out_edges[e.first].push_back(e.second);
      ++remaining;
    }
  std::vector<std::vector<int>> loops;
  while (remaining > 0) {
    auto start_it = std::find_if(out_edges.begin(), out_edges.end(), [](const auto& kv) { return !kv.second.empty(); });
    const int start = start_it->first;
    std::vector<int> loop = {start};
    int prev = start, cur = start_it->second.front();
    start_it->second.erase(start_it->second.begin());
    --remaining;
    while (cur != start) {
      loop.push_back(cur);
      auto& cand = out_edges[cur];
      if (cand.empty()) throw std::logic_error("union_outline: open outline (tiles overlap or leave a gap)");
      // Straight back (along a bridge walked both ways) only when there is no other way on.
      auto turn = [&](int next) { return next == prev ? 4 * M_PI : clockwise_turn(pts[prev] - pts[cur], pts[next] - pts[cur]); };
      size_t best = 0;
      for (size_t k = 1; k < cand.size(); ++k)
        if (turn(cand[k]) < turn(cand[best])) best = k;
      prev = cur;
      cur = cand[best];
      cand.erase(cand.begin() + static_cast<long>(best));
      --remaining;
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

Polygon2 points_of(const std::vector<Vec2>& pts, const std::vector<int>& loop) {
  Polygon2 poly;
  for (int id : loop) poly.push_back(pts[id]);
  return poly;
}

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// Whether segments (a, b) and (p, q) come within tol of each other anywhere but at an end they share.
bool segments_meet(const std::vector<Vec2>& pts, int a, int b, int p, int q, double tol) {
  const int shared = (a == p || a == q) ? a : (b == p || b == q) ? b : -1;
  if (shared >= 0) {  // only a collinear overlap counts
    const int s = shared == a ? b : a, t = (shared == p) ? q : p;
    if (s == t) return true;  // the same segment
    return point_segment_distance(pts[s], pts[shared], pts[t]) <= tol || point_segment_distance(pts[t], pts[shared], pts[s]) <= tol;
  }
  const Vec2 &A = pts[a], &B = pts[b], &P = pts[p], &Q = pts[q];
  const double d1 = cross(B - A, P - A), d2 = cross(B - A, Q - A), d3 = cross(Q - P, A - P), d4 = cross(Q - P, B - P);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return point_segment_distance(P, A, B) <= tol || point_segment_distance(Q, A, B) <= tol ||
         point_segment_distance(A, P, Q) <= tol || point_segment_distance(B, P, Q) <= tol;
}

// A loop's corners: its points that are not in line with their two neighbours.
std::vector<int> corners(const std::vector<Vec2>& pts, const std::vector<int>& loop, double tol) {
  std::vector<int> out;
  for (size_t k = 0; k < loop.size(); ++k) {
    const Vec2 &prev = pts[loop[(k + loop.size() - 1) % loop.size()]], &cur = pts[loop[k]], &next = pts[loop[(k + 1) % loop.size()]];
    if (std::abs(cross(cur - prev, next - prev)) > tol * (next - prev).norm()) out.push_back(loop[k]);
  }
  return out;
}

// Two bridges per hole, each between a corner of the hole and a corner of a loop already joined to an
// outer loop: the shortest that stay inside the region and meet no boundary edge and no other bridge (ties
// by ids). Joined at two corners, every hole splits its region in pieces without a hole, and no new point
// is made. Holes that can reach only other holes wait until one of those is joined.
std::vector<std::pair<int, int>> hole_bridges(const std::vector<Vec2>& pts, const std::vector<std::vector<int>>& loops, double tol) {
  std::vector<std::pair<int, int>> boundary, bridges;
  for (const auto& loop : loops)
    for (size_t k = 0; k < loop.size(); ++k) boundary.emplace_back(loop[k], loop[(k + 1) % loop.size()]);
  auto inside_region = [&](const Vec2& p) {  // even-odd over every loop
    bool in = false;
    for (const auto& [i, j] : boundary) {
      const Vec2 &a = pts[i], &b = pts[j];
      if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) in = !in;
    }
    return in;
  };
  auto usable = [&](int a, int b) {
    for (const auto& [p, q] : boundary)
      if (segments_meet(pts, a, b, p, q, tol)) return false;
    for (const auto& [p, q] : bridges)
      if (segments_meet(pts, a, b, p, q, tol)) return false;
    return inside_region(0.5 * (pts[a] + pts[b]));
  };
  std::vector<char> joined(loops.size(), 0);
  size_t waiting = 0;
  for (size_t l = 0; l < loops.size(); ++l) {
    joined[l] = signed_area(points_of(pts, loops[l])) >= 0;
    waiting += !joined[l];
  }
  for (bool progress = true; waiting > 0 && progress;) {
    progress = false;
    for (size_t h = 0; h < loops.size(); ++h) {
      if (joined[h]) continue;
      std::vector<std::tuple<double, int, int>> candidates;
      for (int a : corners(pts, loops[h], tol))
        for (size_t o = 0; o < loops.size(); ++o)
          if (joined[o])
            for (int b : corners(pts, loops[o], tol)) candidates.emplace_back((pts[a] - pts[b]).norm(), a, b);
      std::sort(candidates.begin(), candidates.end());
      std::vector<std::pair<int, int>> found;
      for (const auto& [len, a, b] : candidates) {
        if (!found.empty() && (a == found[0].first || b == found[0].second)) continue;
        if (!usable(a, b)) continue;
        found.emplace_back(a, b);
        bridges.emplace_back(a, b);
        if (found.size() == 2) break;
      }
      if (found.size() < 2) {  // not now: a later pass may offer a joined neighbour
        bridges.resize(bridges.size() - found.size());
        continue;
      }
      joined[h] = 1;
      --waiting;
      progress = true;
    }
  }
  if (waiting > 0) throw std::logic_error("union_outline_without_holes: no two bridges from a hole to the rest");
  return bridges;
}

}  // namespace

std::vector<Polygon2> union_outline(const std::vector<Polygon2>& tiles, double tol) {
  PointSet set(tol);
  const DirectedEdges edges = outline_edges(tiles, set, tol);
  std::vector<Polygon2> loops;
  for (const auto& loop : trace_loops(set.points(), edges)) loops.push_back(points_of(set.points(), loop));
  return loops;
}

std::vector<Polygon2> union_outline_without_holes(const std::vector<Polygon2>& tiles, double tol) {
  PointSet set(tol);
  DirectedEdges edges = outline_edges(tiles, set, tol);
  const std::vector<Vec2>& pts = set.points();
  const std::vector<std::vector<int>> loops = trace_loops(pts, edges);
  bool any_hole = false;
  for (const auto& loop : loops) any_hole = any_hole || signed_area(points_of(pts, loop)) < 0;
  std::vector<Polygon2> out;
  if (!any_hole) {
    for (const auto& loop : loops) out.push_back(points_of(pts, loop));
    return out;
  }
  // Each bridge walked both ways: the loops traced again are the pieces.
  for (const auto& [a, b] : hole_bridges(pts, loops, tol)) {
    ++edges[{a, b}];
    ++edges[{b, a}];
  }
  for (const auto& loop : trace_loops(pts, edges)) {
    out.push_back(points_of(pts, loop));
    if (signed_area(out.back()) <= 0) throw std::logic_error("union_outline_without_holes: a piece is not a plain outline");
  }
  return out;
}

}  // namespace lc2wf

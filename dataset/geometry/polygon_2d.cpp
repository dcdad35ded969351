#include "dataset/geometry/polygon_2d.h"

#include <algorithm>
#include <cmath>
#include <map>
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

std::vector<Polygon2> union_outline(const std::vector<Polygon2>& tiles, double tol) {
  PointSet set(tol);
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
  // Directed edges, split where another tile's corner lies on them; a stretch walked both ways is inside.
  std::map<std::pair<int, int>, int> count;
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
  std::map<int, std::vector<int>> out_edges;
  int remaining = 0;
  for (const auto& [e, n] : count)
    for (int k = 0; k < n; ++k) {
      out_edges[e.first].push_back(e.second);
      ++remaining;
    }
  std::vector<Polygon2> loops;
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
      size_t best = 0;
      for (size_t k = 1; k < cand.size(); ++k)
        if (clockwise_turn(pts[prev] - pts[cur], pts[cand[k]] - pts[cur]) <
            clockwise_turn(pts[prev] - pts[cur], pts[cand[best]] - pts[cur]))
          best = k;
      prev = cur;
      cur = cand[best];
      cand.erase(cand.begin() + static_cast<long>(best));
      --remaining;
    }
    Polygon2 poly;
    for (int id : loop) poly.push_back(pts[id]);
    loops.push_back(std::move(poly));
  }
  return loops;
}

namespace {

std::vector<Polygon2> outline_without_holes(const std::vector<Polygon2>& tiles, double tol, int depth) {
  std::vector<Polygon2> loops = union_outline(tiles, tol);
  const auto hole = std::find_if(loops.begin(), loops.end(), [](const Polygon2& l) { return signed_area(l) < 0; });
  if (hole == loops.end()) return loops;
  if (depth > 16) throw std::logic_error("union_outline_without_holes: a hole survives 16 cuts");
  double lo = hole->front().x(), hi = lo;
  for (const Vec2& v : *hole) {
    lo = std::min(lo, v.x());
    hi = std::max(hi, v.x());
  }
  const double xc = 0.5 * (lo + hi);
  std::vector<Polygon2> left, right;
  for (const Polygon2& t : tiles) {
    if (Polygon2 l = clip_half_plane(t, -1, 0, xc); !l.empty() && signed_area(l) > tol * tol) left.push_back(std::move(l));
    if (Polygon2 r = clip_half_plane(t, 1, 0, -xc); !r.empty() && signed_area(r) > tol * tol) right.push_back(std::move(r));
  }
  std::vector<Polygon2> out = outline_without_holes(left, tol, depth + 1);
  for (Polygon2& l : outline_without_holes(right, tol, depth + 1)) out.push_back(std::move(l));
  return out;
}

}  // namespace

std::vector<Polygon2> union_outline_without_holes(const std::vector<Polygon2>& tiles, double tol) {
  return outline_without_holes(tiles, tol, 0);
}

}  // namespace lc2wf

#include "dataset/synthetic/block_assembly.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "dataset/geometry/closed_mesh.h"
#include "dataset/geometry/polygon_2d.h"

namespace lc2wf {
namespace {

constexpr double kTol = 1e-7;        // metres: points and heights closer than this are the same
constexpr double kSideStep = 1e-5;   // how far beside a line the roof heights of its two sides are read

// One plane of one block over the part of the block's rectangle where it is the lowest.
struct Piece {
  int block = 0;
  RoofPlane plane;
  Polygon2 region;
};

bool same_plane(const RoofPlane& p, const RoofPlane& q) {
  return std::abs(p.a - q.a) <= 1e-9 && std::abs(p.b - q.b) <= 1e-9 && std::abs(p.c - q.c) <= 1e-7;
}

// The half-plane where plane q lies above plane p, as a*x + b*y + c >= 0 with (a, b) of unit length;
// `everywhere` / `nowhere` when the planes are parallel.
struct Above {
  bool everywhere = false, nowhere = false;
  double a = 0, b = 0, c = 0;
};
Above above(const RoofPlane& q, const RoofPlane& p) {
  Above h;
  const double a = q.a - p.a, b = q.b - p.b, c = q.c - p.c, n = std::hypot(a, b);
  if (n < 1e-12) {
    h.everywhere = c > kTol;
    h.nowhere = !h.everywhere;
    return h;
  }
  h.a = a / n;
  h.b = b / n;
  h.c = c / n;
  return h;
}

Polygon2 rectangle(const RoofedBlock& b) { return {{b.x0, b.y0}, {b.x1, b.y0}, {b.x1, b.y1}, {b.x0, b.y1}}; }

std::vector<Piece> block_pieces(const std::vector<RoofedBlock>& blocks) {
  std::vector<Piece> pieces;
  for (size_t k = 0; k < blocks.size(); ++k) {
    const auto& planes = blocks[k].planes;
    for (size_t j = 0; j < planes.size(); ++j) {
      Polygon2 region = rectangle(blocks[k]);
      for (size_t i = 0; i < planes.size() && !region.empty(); ++i) {
        if (i == j) continue;
        const Above h = above(planes[i], planes[j]);
        if (h.everywhere) continue;
        if (h.nowhere) {  // plane i is as low or lower everywhere: the lower index keeps an equal plane
          if (!(same_plane(planes[i], planes[j]) && j < i)) region.clear();
          continue;
        }
        region = clip_half_plane(region, h.a, h.b, h.c);
      }
      if (!region.empty() && signed_area(region) > 1e-10) pieces.push_back({static_cast<int>(k), planes[j], region});
    }
  }
  return pieces;
}

// The parts of each piece no other block's roof rises above (equal roofs: the lower block index wins).
std::vector<Piece> visible_fragments(const std::vector<Piece>& pieces) {
  std::vector<Piece> out;
  for (const Piece& p : pieces) {
    std::vector<Polygon2> frags = {p.region};
    for (const Piece& q : pieces) {
      if (q.block == p.block || frags.empty()) continue;
      const Above h = above(q.plane, p.plane);
      Polygon2 cut;
      if (h.everywhere || (h.nowhere && same_plane(q.plane, p.plane) && q.block < p.block)) cut = q.region;
      else if (!h.nowhere) cut = clip_half_plane(q.region, h.a, h.b, h.c, 0.0);
      if (cut.empty()) continue;
      std::vector<Polygon2> next;
      for (const Polygon2& f : frags)
        for (Polygon2& g : subtract_convex(f, cut)) next.push_back(std::move(g));
      frags = std::move(next);
    }
    for (Polygon2& f : frags) out.push_back({p.block, p.plane, std::move(f)});
  }
  return out;
}

// The roof plane on top of point (x, y), or nullptr on open ground.
const RoofPlane* roof_on_top(const std::vector<RoofedBlock>& blocks, double x, double y) {
  const RoofPlane* best = nullptr;
  double best_z = -std::numeric_limits<double>::infinity();
  for (const RoofedBlock& b : blocks) {
    if (!(x > b.x0 && x < b.x1 && y > b.y0 && y < b.y1)) continue;
    const RoofPlane* low = &b.planes[0];
    for (const RoofPlane& q : b.planes)
      if (q.at(x, y) < low->at(x, y)) low = &q;
    if (low->at(x, y) > best_z) {
      best_z = low->at(x, y);
      best = low;
    }
  }
  return best;
}

std::vector<double> distinct_sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > kTol) out.push_back(x);
  return out;
}

// Walls on the line x = c (axis 0) or y = c (axis 1): between the roof heights on its two sides wherever
// they differ, facing the lower side. Returns the faces of the line, coplanar pieces merged.
void add_line_walls(const std::vector<RoofedBlock>& blocks, const std::vector<Piece>& frags, int axis, double c,
                    std::vector<PointFace>& faces) {
  auto point = [&](double s) { return axis == 0 ? Vec2(c, s) : Vec2(s, c); };
  std::vector<double> breaks;
  for (const RoofedBlock& b : blocks) {
    breaks.push_back(axis == 0 ? b.y0 : b.x0);
    breaks.push_back(axis == 0 ? b.y1 : b.x1);
  }
  for (const Piece& f : frags) {
    for (size_t k = 0; k < f.region.size(); ++k) {
      const Vec2 p = f.region[k], q = f.region[(k + 1) % f.region.size()];
      const double dp = p[axis] - c, dq = q[axis] - c;
      if (std::abs(dp) <= kTol) breaks.push_back(p[1 - axis]);
      if ((dp > kTol && dq < -kTol) || (dp < -kTol && dq > kTol)) breaks.push_back(p[1 - axis] + (q[1 - axis] - p[1 - axis]) * dp / (dp - dq));
    }
  }
  breaks = distinct_sorted(breaks);
  // Pieces of wall per facing side (0: facing the low-coordinate side, 1: the high side), in (s, z).
  std::vector<Polygon2> walls[2];
  auto add_piece = [&](double s0, double s1, double lo0, double lo1, double hi0, double hi1, int facing) {
    walls[facing].push_back({{s0, lo0}, {s1, lo1}, {s1, hi1}, {s0, hi0}});
  };
  for (size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double s0 = breaks[i], s1 = breaks[i + 1], mid = 0.5 * (s0 + s1);
    Vec2 below = point(mid), beyond = point(mid);
    below[axis] -= kSideStep;
    beyond[axis] += kSideStep;
    const RoofPlane* pm = roof_on_top(blocks, below.x(), below.y());
    const RoofPlane* pp = roof_on_top(blocks, beyond.x(), beyond.y());
    auto z = [&](const RoofPlane* pl, double s) { return pl ? pl->at(point(s).x(), point(s).y()) : 0.0; };
    const double m0 = z(pm, s0), m1 = z(pm, s1), p0 = z(pp, s0), p1 = z(pp, s1);
    const double d0 = p0 - m0, d1 = p1 - m1;
    if (std::abs(d0) <= kTol && std::abs(d1) <= kTol) continue;
    auto emit = [&](double a, double b, double ma, double mb, double pa, double pb) {
      const bool minus_lower = (pa - ma) + (pb - mb) > 0;
      if (minus_lower) add_piece(a, b, ma, mb, pa, pb, 0);
      else add_piece(a, b, pa, pb, ma, mb, 1);
    };
    if ((d0 > kTol && d1 < -kTol) || (d0 < -kTol && d1 > kTol)) {  // the two roofs cross: two pieces
      const double sc = s0 + (s1 - s0) * d0 / (d0 - d1), mc = z(pm, sc), pc = z(pp, sc);
      emit(s0, sc, m0, mc, p0, pc);
      emit(sc, s1, mc, m1, pc, p1);
    } else {
      emit(s0, s1, m0, m1, p0, p1);
    }
  }
  for (int facing = 0; facing < 2; ++facing) {
    if (walls[facing].empty()) continue;
    for (const Polygon2& loop : union_outline_without_holes(walls[facing], kTol)) {
      PointFace face;
      face.label = FaceLabel::Wall;
      for (const Vec2& sz : loop) face.points.push_back(axis == 0 ? Vec3(c, sz.x(), sz.y()) : Vec3(sz.x(), c, sz.y()));
      // Counter-clockwise in (y, z) faces +x; in (x, z) it faces -y.
      const bool faces_high_side = facing == 1;
      if ((axis == 0) != faces_high_side) std::reverse(face.points.begin(), face.points.end());
      faces.push_back(std::move(face));
    }
  }
}

}  // namespace

double RoofedBlock::roof_at(double x, double y) const {
  double z = std::numeric_limits<double>::infinity();
  for (const RoofPlane& p : planes) z = std::min(z, p.at(x, y));
  return z;
}

void RoofedBlock::Check() const {
  if (!(std::isfinite(x0) && std::isfinite(x1) && std::isfinite(y0) && std::isfinite(y1)))
    throw std::invalid_argument("RoofedBlock: corners must be finite");
  if (!(x1 - x0 >= 0.01 && y1 - y0 >= 0.01)) throw std::invalid_argument("RoofedBlock: x1 - x0 and y1 - y0 must be >= 0.01 m");
  if (planes.empty()) throw std::invalid_argument("RoofedBlock: needs at least one roof plane");
  // The roof is concave (lowest of planes): its lowest point over the rectangle is a corner.
  for (const auto& [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}})
    if (!(roof_at(x, y) > 0.01)) throw std::invalid_argument("RoofedBlock: the roof must stay above the ground");
}

PolyMesh assemble_blocks(const std::vector<RoofedBlock>& blocks) {
  if (blocks.empty()) throw std::invalid_argument("assemble_blocks: no block");
  for (const RoofedBlock& b : blocks) b.Check();
  const std::vector<Piece> frags = visible_fragments(block_pieces(blocks));
  std::vector<PointFace> faces;
  // Roof: visible fragments grouped by plane, each group's outline one face per loop.
  std::vector<bool> done(frags.size(), false);
  for (size_t i = 0; i < frags.size(); ++i) {
    if (done[i]) continue;
    std::vector<Polygon2> group;
    for (size_t j = i; j < frags.size(); ++j)
      if (!done[j] && same_plane(frags[j].plane, frags[i].plane)) {
        group.push_back(frags[j].region);
        done[j] = true;
      }
    for (const Polygon2& loop : union_outline_without_holes(group, kTol)) {
      PointFace face;
      face.label = FaceLabel::Roof;
      for (const Vec2& p : loop) face.points.emplace_back(p.x(), p.y(), frags[i].plane.at(p.x(), p.y()));
      faces.push_back(std::move(face));
    }
  }
  // Base: the footprint, facing down.
  std::vector<Polygon2> footprint;
  for (const Piece& f : frags) footprint.push_back(f.region);
  for (const Polygon2& loop : union_outline_without_holes(footprint, kTol)) {
    PointFace face;
    face.label = FaceLabel::Base;
    for (auto it = loop.rbegin(); it != loop.rend(); ++it) face.points.emplace_back(it->x(), it->y(), 0.0);
    faces.push_back(std::move(face));
  }
  // Walls on every line a block's side lies on.
  std::vector<double> lines[2];
  for (const RoofedBlock& b : blocks) {
    lines[0].insert(lines[0].end(), {b.x0, b.x1});
    lines[1].insert(lines[1].end(), {b.y0, b.y1});
  }
  for (int axis = 0; axis < 2; ++axis)
    for (double c : distinct_sorted(lines[axis])) add_line_walls(blocks, frags, axis, c, faces);
  return mesh_from_faces(faces);
}

}  // namespace lc2wf

#include "infer/surfaces/prism_shell.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "infer/surfaces/polygon_geometry.h"
#include "infer/surfaces/shell_assembly.h"

namespace lc2wf {
namespace {

using EdgeKey = std::pair<int, int>;

std::optional<SurfaceModel> fail(std::string* why, const std::string& reason) {
  if (why) *why = reason;
  return std::nullopt;
}

std::optional<RoofSheet> fail_sheet(std::string* why, const std::string& reason) {
  if (why) *why = reason;
  return std::nullopt;
}

Vec2 plan(const Vec3& p) { return {p.x(), p.y()}; }

// The border of the sheet: its sides that one face uses, as loops in the faces' direction; nullopt when the
// border is pinched (a vertex it passes twice).
std::optional<std::vector<std::vector<int>>> border_loops(const std::vector<std::vector<int>>& rings) {
  std::set<EdgeKey> directed;
  for (const auto& r : rings)
    for (size_t i = 0; i < r.size(); ++i) directed.insert({r[i], r[(i + 1) % r.size()]});
  std::map<int, int> next;
  for (const auto& [p, q] : directed)
    if (!directed.count({q, p}) && !next.emplace(p, q).second) return std::nullopt;
  std::vector<std::vector<int>> loops;
  std::set<int> done;
  for (const auto& [first, unused] : next) {
    if (done.count(first)) continue;
    std::vector<int> loop;
    int v = first;
    do {
      loop.push_back(v);
      done.insert(v);
      const auto it = next.find(v);
      if (it == next.end()) return std::nullopt;
      v = it->second;
    } while (v != first && loop.size() <= next.size());
    if (v != first) return std::nullopt;
    loops.push_back(std::move(loop));
  }
  return loops;
}

double plan_area(const std::vector<int>& ring, const std::vector<Vec3>& V) {
  std::vector<Vec2> p;
  for (int v : ring) p.push_back(plan(V[v]));
  return signed_area(p);
}

// A face's plan (its ring seen from above) and plane; `simple` false for a plan that folds or has no area.
struct PlanFace {
  std::vector<Vec2> plan;
  Plane plane;
  bool simple = false;
  double area = 0;
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  // the plan's box
  double z_at(const Vec2& p) const { return (plane.offset - plane.normal.x() * p.x() - plane.normal.y() * p.y()) / plane.normal.z(); }
};

// Sum over sample points of a's plan inside b's of (b's height - a's height): positive when b lies above a there.
double height_above(const PlanFace& a, const PlanFace& b) {
  double sum = 0;
  for (const auto& t : triangulate_polygon(a.plan)) {
    const Vec2 p = (a.plan[t[0]] + a.plan[t[1]] + a.plan[t[2]]) / 3;
    if (point_in_polygon(p, b.plan)) sum += b.z_at(p) - a.z_at(p);
  }
  return sum;
}

bool boxes_meet(const PlanFace& a, const PlanFace& b) {
  return a.lo.x() < b.hi.x() && b.lo.x() < a.hi.x() && a.lo.y() < b.hi.y() && b.lo.y() < a.hi.y();
}

// Seen from above, a roof hides what lies under it: of two faces whose plans overlap (by more than
// `min_overlap` of the smaller), the lower one is no roof (the eave level's horizontal cycles, ceilings).
// Stops (nullopt) when `budget` cannot pay for the pairs of faces compared.
std::optional<std::vector<bool>> hidden_faces(const std::vector<std::vector<int>>& rings, const std::vector<Vec3>& V,
                                              double min_overlap, double wall_tilt_deg, WorkBudget* budget) {
  const double min_nz = std::sin(wall_tilt_deg * M_PI / 180);  // walls have no plan to hide anything with
  std::vector<PlanFace> faces(rings.size());
  for (size_t f = 0; f < rings.size(); ++f) {
    const long r = static_cast<long>(rings[f].size());
    if (budget && !budget->charge(r * r, "roof sheet")) return std::nullopt;  // the plan's simplicity test
    std::vector<Vec3> pts;
    for (int v : rings[f]) pts.push_back(V[v]), faces[f].plan.push_back(plan(V[v]));
    faces[f].plane = fit_plane(pts);
    faces[f].area = std::abs(signed_area(faces[f].plan));
    faces[f].simple = std::abs(faces[f].plane.normal.z()) > min_nz && faces[f].area > 0 && !polygon_self_intersects(faces[f].plan, 1e-9);
    if (!faces[f].plan.empty()) {
      faces[f].lo = faces[f].hi = faces[f].plan[0];
      for (const Vec2& p : faces[f].plan) faces[f].lo = faces[f].lo.cwiseMin(p), faces[f].hi = faces[f].hi.cwiseMax(p);
    }
  }
  std::vector<bool> hidden(rings.size(), false);
  for (size_t a = 0; a < faces.size(); ++a) {
    if (budget && !budget->charge(static_cast<long>(faces.size() - a), "roof sheet")) return std::nullopt;  // box tests
    for (size_t b = a + 1; b < faces.size(); ++b) {
      if (!faces[a].simple || !faces[b].simple || !boxes_meet(faces[a], faces[b])) continue;
      // Triangulations (ear clipping), their pairs clipped against each other, the height samples.
      const long ra = static_cast<long>(faces[a].plan.size()), rb = static_cast<long>(faces[b].plan.size());
      if (budget && !budget->charge(4 * ra * rb + 2 * (ra * ra * ra + rb * rb * rb), "roof sheet")) return std::nullopt;
      const double overlap = intersection_area(faces[a].plan, faces[b].plan);
      if (overlap <= min_overlap * std::min(faces[a].area, faces[b].area)) continue;
      const double b_above = height_above(faces[a], faces[b]) - height_above(faces[b], faces[a]);
      hidden[b_above > 0 ? a : b] = true;
    }
  }
  return hidden;
}

// The sheet's parts (faces linked by shared sides), largest plan first.
std::vector<std::vector<int>> sheet_parts(const std::vector<std::vector<int>>& rings, const std::vector<Vec3>& V) {
  std::vector<int> parent(rings.size());
  for (size_t f = 0; f < rings.size(); ++f) parent[f] = static_cast<int>(f);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<EdgeKey, int> first;
  for (size_t f = 0; f < rings.size(); ++f)
    for (size_t i = 0; i < rings[f].size(); ++i) {
      const int p = rings[f][i], q = rings[f][(i + 1) % rings[f].size()];
      const auto [it, fresh] = first.emplace(EdgeKey{std::min(p, q), std::max(p, q)}, static_cast<int>(f));
      if (!fresh) parent[root(static_cast<int>(f))] = root(it->second);
    }
  std::map<int, std::vector<int>> groups;
  std::map<int, double> area;
  for (size_t f = 0; f < rings.size(); ++f) {
    groups[root(static_cast<int>(f))].push_back(static_cast<int>(f));
    area[root(static_cast<int>(f))] += std::abs(plan_area(rings[f], V));
  }
  std::vector<std::pair<double, std::vector<int>>> sorted;
  for (auto& [r, g] : groups) sorted.push_back({area[r], std::move(g)});
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<std::vector<int>> out;
  for (auto& [a, g] : sorted) out.push_back(std::move(g));
  return out;
}

// Walls and ground under one outline loop (counter-clockwise in plan), appended to `out` (its vertices are
// the sheet's; new ground vertices are appended). False, with the reason, when the outline is no footprint.
bool extrude_outline(std::vector<int> loop, const PrismOptions& o, SurfaceModel& out, std::string* why) {
  const std::vector<Vec3> V = out.vertices;
  const auto no = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  // Wall corners ("columns"): runs of outline vertices on one vertical line (steps between roof levels).
  const double sin_tilt = std::sin(o.wall_tilt_deg * M_PI / 180);
  const auto same_column = [&](int a, int b) {
    const Vec3 d = V[b] - V[a];
    return plan(d).norm() <= std::max(o.column_distance, sin_tilt * d.norm());
  };
  const size_t n = loop.size();
  size_t start = n;
  for (size_t i = 0; i < n && start == n; ++i)
    if (!same_column(loop[(i + n - 1) % n], loop[i])) start = i;
  if (start == n) return no("the roof outline has no extent in plan");
  std::rotate(loop.begin(), loop.begin() + static_cast<long>(start), loop.end());
  std::vector<std::vector<int>> columns;
  for (int v : loop) {
    if (columns.empty() || !same_column(columns.back().back(), v)) columns.push_back({});
    columns.back().push_back(v);
  }
  const size_t c = columns.size();
  if (c < 3) return no("the roof outline has fewer than three corners in plan");
  std::vector<Vec2> where(c, Vec2::Zero());
  for (size_t k = 0; k < c; ++k) {
    const auto& col = columns[k];
    for (size_t i = 0; i + 1 < col.size(); ++i)
      if ((V[col[i + 1]].z() > V[col[i]].z()) != (V[col[1]].z() > V[col[0]].z()))
        return no("the roof outline goes up and down on one wall corner");
    for (int v : col) where[k] += plan(V[v]);
    where[k] /= static_cast<double>(col.size());
  }
  // Corners where the plan turns; the columns between them lie on one straight wall.
  const double cos_straight = std::cos(o.straight_deg * M_PI / 180);
  std::vector<size_t> corners;
  for (size_t k = 0; k < c; ++k) {
    const Vec2 a = (where[k] - where[(k + c - 1) % c]).normalized(), b = (where[(k + 1) % c] - where[k]).normalized();
    if (a.dot(b) < cos_straight) corners.push_back(k);
  }
  if (corners.size() < 3) return no("the roof outline has fewer than three corners in plan");
  std::vector<Vec2> footprint;
  for (size_t k : corners) footprint.push_back(where[k]);
  const double eps = std::max(1e-9, 0.25 * o.column_distance);
  if (signed_area(footprint) <= eps * eps || polygon_self_intersects(footprint, eps))
    return no("the roof outline folds over itself in plan");

  std::vector<int> ground(c, -1);
  for (size_t k : corners) {
    ground[k] = static_cast<int>(out.vertices.size());
    out.vertices.emplace_back(where[k].x(), where[k].y(), o.ground_z);
  }
  for (size_t i = 0; i < corners.size(); ++i) {
    const size_t a = corners[i], b = corners[(i + 1) % corners.size()];
    // Seen from outside, counter-clockwise: along the ground, up corner b to where the outline reaches it,
    // back along the outline to where it leaves corner a, down corner a.
    std::vector<int> ring{ground[a], ground[b]};
    const std::vector<int>& cb = columns[b];
    std::vector<int> below_b(cb.begin() + 1, cb.end());
    std::sort(below_b.begin(), below_b.end(), [&](int x, int y) { return V[x].z() < V[y].z(); });
    for (int v : below_b)
      if (V[v].z() < V[cb.front()].z()) ring.push_back(v);
    for (size_t k = b;; k = (k + c - 1) % c) {
      const std::vector<int>& col = columns[k];
      if (k == b) {
        ring.push_back(col.front());
        continue;
      }
      if (k == a) {
        ring.push_back(col.back());
        break;
      }
      ring.insert(ring.end(), col.rbegin(), col.rend());
    }
    const std::vector<int>& ca = columns[a];
    std::vector<int> below_a(ca.begin(), ca.end() - 1);
    std::sort(below_a.begin(), below_a.end(), [&](int x, int y) { return V[x].z() > V[y].z(); });
    for (int v : below_a)
      if (V[v].z() < V[ca.back()].z()) ring.push_back(v);
    out.faces.push_back({std::move(ring), SurfaceLabel::kWall});
  }
  std::vector<int> floor;
  for (size_t i = corners.size(); i-- > 0;) floor.push_back(ground[corners[i]]);
  out.faces.push_back({std::move(floor), SurfaceLabel::kGround});

  return true;
}

}  // namespace

std::optional<RoofSheet> roof_sheet(const SurfaceModel& m, const PrismOptions& o, std::string* why, WorkBudget* budget) {
  const auto& V = m.vertices;
  RoofSheet sheet;
  auto& top = sheet.faces;
  auto& top_labels = sheet.labels;
  for (const SurfaceFace& f : m.faces) {
    if (f.label == SurfaceLabel::kGround || f.ring.size() < 3) continue;
    double low = INFINITY;
    for (int v : f.ring) low = std::min(low, V[v].z());
    if (low <= o.ground_z + o.level_distance) continue;  // a wall down to the ground: rebuilt from the outline
    top.push_back(f.ring);
    top_labels.push_back(f.label);
  }
  const std::optional<std::vector<bool>> hidden_or_stopped = hidden_faces(top, V, o.min_overlap, o.wall_tilt_deg, budget);
  if (!hidden_or_stopped) return fail_sheet(why, budget->reason());
  const std::vector<bool>& hidden = *hidden_or_stopped;
  for (size_t f = top.size(); f-- > 0;)
    if (hidden[f]) top.erase(top.begin() + static_cast<long>(f)), top_labels.erase(top_labels.begin() + static_cast<long>(f));
  if (top.empty()) return fail_sheet(why, "no roof face above the ground level");
  std::map<EdgeKey, int> uses;
  for (const auto& r : top)
    for (size_t i = 0; i < r.size(); ++i) {
      const int p = r[i], q = r[(i + 1) % r.size()];
      if (++uses[{std::min(p, q), std::max(p, q)}] > 2) return fail_sheet(why, "a roof side bounds three or more roof faces");
    }
  if (!orient_faces(top, V, nullptr)) return fail_sheet(why, "the roof faces cannot be oriented consistently");
  double up = 0;  // the sheet faces upwards: its outline then runs counter-clockwise in plan
  for (const auto& r : top) {
    std::vector<Vec3> pts;
    for (int v : r) pts.push_back(V[v]);
    up += newell_normal(pts).z();
  }
  if (up < 0)
    for (auto& r : top) std::reverse(r.begin(), r.end());
  sheet.parts = sheet_parts(top, V);
  return sheet;
}

std::optional<SurfaceModel> extrude_roof_sheet(const SurfaceModel& m, const RoofSheet& sheet, const PrismOptions& o, std::string* why) {
  const auto& top = sheet.faces;
  const auto& top_labels = sheet.labels;
  const auto& parts = sheet.parts;
  SurfaceModel out;
  out.vertices = m.vertices;
  std::string reason;
  for (size_t k = 0; k < parts.size(); ++k) {
    if (!o.parts.empty() && (k >= o.parts.size() || !o.parts[k])) continue;
    const std::vector<int>& part = parts[k];
    std::vector<std::vector<int>> rings;
    for (int f : part) rings.push_back(top[f]);
    const auto loops = border_loops(rings);
    std::string part_why = "the roof outline is not one loop (a hole or a pinch)";
    SurfaceModel with = out;
    if (loops && loops->size() == 1 && extrude_outline(loops->front(), o, with, &part_why)) {
      for (int f : part) with.faces.push_back({top[f], top_labels[f]});
      out = std::move(with);
    } else if (reason.empty()) {
      reason = part_why;
    }
    if (out.faces.empty()) break;  // a part that fails alone is left out, but not the first one asked for
  }
  if (out.faces.empty()) return fail(why, reason);
  if (why) *why = reason;
  // Only the vertices the faces use, in order of first use.
  std::map<int, int> renumber;
  std::vector<Vec3> used;
  for (SurfaceFace& f : out.faces)
    for (int& v : f.ring) {
      const auto [it, fresh] = renumber.emplace(v, static_cast<int>(used.size()));
      if (fresh) used.push_back(out.vertices[v]);
      v = it->second;
    }
  out.vertices = std::move(used);
  return out;
}

std::optional<SurfaceModel> extrude_roof_to_ground(const SurfaceModel& m, const PrismOptions& o, std::string* why, int* part_count) {
  const std::optional<RoofSheet> sheet = roof_sheet(m, o, why);
  if (!sheet) return std::nullopt;
  if (part_count) *part_count = static_cast<int>(sheet->parts.size());
  return extrude_roof_sheet(m, *sheet, o, why);
}

}  // namespace lc2wf

#include "infer/surfaces/wireframe_surfaces.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "infer/surfaces/face_labels.h"
#include "infer/surfaces/plane_faces.h"
#include "infer/surfaces/prism_shell.h"
#include "infer/surfaces/shell_assembly.h"
#include "infer/surfaces/wireframe_cleanup.h"
#include "infer/surfaces/work_budget.h"

namespace lc2wf {
namespace {

using EdgeKey = std::pair<int, int>;

struct Attempt {
  SurfaceModel model;
  ShellCheck check;
  std::vector<int> source;  // model vertex -> junction id of the wireframe it was built from
  bool stopped = false;     // the work budget ran out: no model
  int defects() const { return check.open_edges + check.overused_edges + check.intersecting_face_pairs + check.self_intersecting_faces; }
};

double tiny(const SurfaceOptions& o) { return std::max(1e-6, 0.25 * o.merge_distance_m); }

bool set_status(Attempt& a, const std::vector<std::string>& reasons, const SurfaceOptions& o, WorkBudget& budget);

// Adds the sides that close open chains: those two planes ask for, or one plane whose two chain ends are each
// other's nearest and at least three edges apart. Two rounds, so a plane made only of closed sides (the ground
// under completed walls) closes too. Returns the candidate planes of the final graph when the last round
// found them (it added nothing), so the caller need not search them again.
std::optional<std::vector<CandidatePlane>> close_gaps(Wireframe& wf, std::set<EdgeKey>& added, const SurfaceOptions& o,
                                                      WorkBudget& budget) {
  for (int round = 0; round < 2; ++round) {
    std::set<EdgeKey> existing;
    for (const auto& e : wf.edges) existing.insert({e[0], e[1]});
    std::map<EdgeKey, std::pair<int, bool>> votes;
    std::vector<CandidatePlane> planes = candidate_planes(wf, o, &budget);
    for (const CandidatePlane& p : planes)
      for (const ClosingEdge& c : closing_edges(wf, p, tiny(o), &budget)) {
        auto& v = votes[{c.ends[0], c.ends[1]}];
        ++v.first;
        // One plane alone closes only a chain of three or more edges: any two edges at a corner span a plane.
        v.second = v.second || (c.mutual_nearest && c.chain_edges >= 3);
      }
    int fresh = 0;
    for (const auto& [k, v] : votes)
      if (!existing.count(k) && (v.first >= 2 || v.second)) {
        wf.edges.push_back({k.first, k.second});
        added.insert(k);
        ++fresh;
      }
    if (budget.exhausted()) return std::nullopt;
    if (fresh == 0) return planes;
  }
  return std::nullopt;
}

// Clean wireframe -> gaps closed -> candidate planes -> faces per plane -> shell. `stopped` when the budget ran out.
Attempt build(const Wireframe& cleaned, const SurfaceOptions& o, WorkBudget& budget) {
  Attempt stopped;
  stopped.stopped = true;
  Wireframe wf = cleaned;
  std::set<EdgeKey> added;
  std::optional<std::vector<CandidatePlane>> found = close_gaps(wf, added, o, budget);
  if (budget.exhausted()) return stopped;
  const std::vector<CandidatePlane> planes = found ? std::move(*found) : candidate_planes(wf, o, &budget);
  if (budget.exhausted()) return stopped;
  std::vector<CandidateFace> candidates;
  std::set<std::vector<int>> seen;
  for (size_t p = 0; p < planes.size(); ++p)
    for (std::vector<int>& ring : plane_cycles(wf, planes[p], tiny(o), &budget)) {
      std::vector<int> sorted = ring;
      std::sort(sorted.begin(), sorted.end());
      if (seen.insert(sorted).second) candidates.push_back({std::move(ring), static_cast<int>(p)});
    }
  if (budget.exhausted()) return stopped;
  long candidate_sides = 0;
  for (const CandidateFace& f : candidates) candidate_sides += static_cast<long>(f.ring.size());
  // Selection (a heap over the faces, each removal updating its neighbours), merge, orientation, snapping.
  if (!budget.charge(32 * candidate_sides, "shell assembly")) return stopped;
  std::vector<CandidateFace> kept;
  for (int f : select_shell_faces(candidates, added)) kept.push_back(candidates[f]);
  const std::vector<CandidateFace> merged = merge_coplanar_faces(kept, wf.junctions, o.plane_angle_deg);

  Attempt a;
  std::vector<std::vector<int>> rings;
  std::map<int, int> local;
  for (const CandidateFace& f : merged) {
    std::vector<int> r;
    for (int j : f.ring) {
      const auto [it, fresh] = local.emplace(j, static_cast<int>(a.source.size()));
      if (fresh) a.source.push_back(j);
      r.push_back(it->second);
    }
    rings.push_back(std::move(r));
  }
  for (int j : a.source) a.model.vertices.push_back(wf.junctions[j]);
  std::vector<std::string> reasons;
  orient_faces(rings, a.model.vertices, &reasons);
  snap_vertices_to_planes(a.model.vertices, rings, 2 * o.plane_distance_m);
  for (auto& r : rings) a.model.faces.push_back({std::move(r), SurfaceLabel::kRoof});
  label_faces(a.model, o.wall_tilt_deg, o.plane_distance_m);
  if (!set_status(a, reasons, o, budget)) return stopped;
  return a;
}

// The checks and the status; false (nothing set) when the budget cannot pay for the checks.
bool set_status(Attempt& a, const std::vector<std::string>& reasons, const SurfaceOptions& o, WorkBudget& budget) {
  a.check = check_shell(a.model, o.planarity_tolerance_m, &budget);
  if (budget.exhausted()) return false;
  if (a.model.faces.empty()) {
    a.model.status = ShellStatus::kNoFaces;
    a.model.reasons = {"no planar cycle of edges bounds a face"};
  } else if (a.check.valid_solid() && reasons.empty()) {
    a.model.status = ShellStatus::kClosedSolid;
  } else {
    a.model.status = ShellStatus::kOpenSurfaces;
    a.model.reasons = reasons;
    for (std::string& p : a.check.problems())
      if (std::find(a.model.reasons.begin(), a.model.reasons.end(), p) == a.model.reasons.end()) a.model.reasons.push_back(std::move(p));
  }
  return true;
}

// Walls down from the eaves: every end of a horizontal open side of a roof face gets a vertical edge to the
// ground level, the lowest end of the wireframe's vertical edges. Nothing when there is no vertical edge
// (the ground's height is unknown) or nothing to add.
bool complete_walls(Wireframe& wf, const Attempt& a, const SurfaceOptions& o) {
  const double cos_vertical = std::cos(o.wall_tilt_deg * M_PI / 180);
  const auto vertical = [&](const std::array<int, 2>& e) {
    const Vec3 d = wf.junctions[e[1]] - wf.junctions[e[0]];
    return d.norm() > 0 && std::abs(d.z()) >= cos_vertical * d.norm();
  };
  double ground = INFINITY;
  std::vector<bool> has_down(wf.junctions.size(), false);
  for (const auto& e : wf.edges) {
    if (!vertical(e)) continue;
    const int lo = wf.junctions[e[0]].z() < wf.junctions[e[1]].z() ? e[0] : e[1];
    ground = std::min(ground, wf.junctions[lo].z());
    has_down[lo == e[0] ? e[1] : e[0]] = true;
  }
  if (!std::isfinite(ground)) return false;
  std::map<EdgeKey, int> uses;
  for (const SurfaceFace& f : a.model.faces)
    for (size_t i = 0; i < f.ring.size(); ++i) {
      const int p = a.source[f.ring[i]], q = a.source[f.ring[(i + 1) % f.ring.size()]];
      ++uses[{std::min(p, q), std::max(p, q)}];
    }
  std::set<int> eave_corners;
  for (const SurfaceFace& f : a.model.faces) {
    if (f.label != SurfaceLabel::kRoof) continue;
    for (size_t i = 0; i < f.ring.size(); ++i) {
      const int p = a.source[f.ring[i]], q = a.source[f.ring[(i + 1) % f.ring.size()]];
      if (uses[{std::min(p, q), std::max(p, q)}] != 1) continue;
      const Vec3 &pp = wf.junctions[p], &pq = wf.junctions[q];
      if (std::abs(pp.z() - pq.z()) > o.plane_distance_m) continue;
      if (std::min(pp.z(), pq.z()) <= ground + o.plane_distance_m) continue;
      for (int j : {p, q})
        if (!has_down[j]) eave_corners.insert(j);
    }
  }
  if (eave_corners.empty()) return false;
  for (int j : eave_corners) {
    const Vec3 foot(wf.junctions[j].x(), wf.junctions[j].y(), ground);
    int id = -1;
    for (size_t k = 0; k < wf.junctions.size() && id < 0; ++k)
      if ((wf.junctions[k] - foot).norm() <= std::max(o.merge_distance_m, 1e-9)) id = static_cast<int>(k);
    if (id < 0) {
      id = static_cast<int>(wf.junctions.size());
      wf.junctions.push_back(foot);
    }
    wf.edges.push_back({std::min(j, id), std::max(j, id)});
  }
  return true;
}

// The ground level: the mean height of the junctions at the lowest end of the vertical edges (within the
// plane tolerance of it). None without vertical edges: a roof alone says nothing about the ground.
std::optional<double> ground_level(const Wireframe& wf, const SurfaceOptions& o) {
  const double cos_vertical = std::cos(o.wall_tilt_deg * M_PI / 180);
  double lowest = INFINITY;
  for (const auto& e : wf.edges) {
    const Vec3 d = wf.junctions[e[1]] - wf.junctions[e[0]];
    if (d.norm() > 0 && std::abs(d.z()) >= cos_vertical * d.norm())
      lowest = std::min({lowest, wf.junctions[e[0]].z(), wf.junctions[e[1]].z()});
  }
  if (!std::isfinite(lowest)) return std::nullopt;
  double sum = 0;
  int count = 0;
  for (const Vec3& p : wf.junctions)
    if (std::abs(p.z() - lowest) <= o.plane_distance_m) sum += p.z(), ++count;
  return sum / count;
}

// A shell whose lowest point lies above the ground level is a roof closed by a lid at the eaves (the eaves'
// horizontal cycle), not the building: the walls below were not found.
bool floats_above(const SurfaceModel& m, double ground, const SurfaceOptions& o) {
  double lowest = INFINITY;
  for (const Vec3& p : m.vertices) lowest = std::min(lowest, p.z());
  return lowest > ground + o.plane_distance_m;
}

PrismOptions prism_options(double ground, const SurfaceOptions& o) {
  PrismOptions p;
  p.ground_z = ground;
  p.level_distance = o.plane_distance_m;
  p.column_distance = o.merge_distance_m;
  p.wall_tilt_deg = o.wall_tilt_deg;
  p.straight_deg = o.plane_angle_deg;
  return p;
}

// The shell as a prism below the parts of the roof sheet of `a` (prism_shell.h), its vertices on their faces'
// planes. nullopt when the sheet gives no prism or the budget ran out.
std::optional<Attempt> prism_attempt(const Attempt& a, const RoofSheet& sheet, double ground, const SurfaceOptions& o,
                                     const std::vector<bool>& parts, WorkBudget& budget) {
  long sheet_sides = 0;
  for (const auto& r : sheet.faces) sheet_sides += static_cast<long>(r.size());
  if (!budget.charge(8 * sheet_sides, "prism below the roof")) return std::nullopt;  // outlines, walls, orientation, snapping
  PrismOptions p = prism_options(ground, o);
  p.parts = parts;
  std::optional<SurfaceModel> m = extrude_roof_sheet(a.model, sheet, p);
  if (!m) return std::nullopt;
  Attempt out;
  out.model = std::move(*m);
  std::vector<std::vector<int>> rings;
  for (const SurfaceFace& f : out.model.faces) rings.push_back(f.ring);
  std::vector<std::string> reasons;
  orient_faces(rings, out.model.vertices, &reasons);
  snap_vertices_to_planes(out.model.vertices, rings, 2 * o.plane_distance_m);
  for (size_t f = 0; f < rings.size(); ++f) out.model.faces[f].ring = std::move(rings[f]);
  if (!set_status(out, reasons, o, budget)) return std::nullopt;
  return out;
}

// The prism under every part of the roof sheet when it is a valid solid; else greedily from the largest part,
// each further part kept when the solid stays valid (two prisms side by side overlap where they touch).
// nullopt when there is none or the budget ran out.
std::optional<Attempt> closed_prism(const Attempt& a, double ground, const SurfaceOptions& o, WorkBudget& budget) {
  // The sheet once for every choice of parts.
  const std::optional<RoofSheet> sheet = roof_sheet(a.model, prism_options(ground, o), nullptr, &budget);
  if (!sheet) return std::nullopt;
  std::optional<Attempt> all = prism_attempt(a, *sheet, ground, o, {}, budget);
  if (all && all->model.closed_solid()) return all;
  const int count = static_cast<int>(sheet->parts.size());
  if (count < 2 || budget.exhausted()) return std::nullopt;
  // Each try re-checks the whole shell: the largest parts only, so the time stays a few checks, not one per part.
  constexpr int kMaxGreedyParts = 16;
  std::vector<bool> parts(count, false);
  std::optional<Attempt> best;
  for (int k = 0; k < std::min(count, kMaxGreedyParts); ++k) {
    parts[k] = true;
    std::optional<Attempt> p = prism_attempt(a, *sheet, ground, o, parts, budget);
    if (budget.exhausted()) return std::nullopt;
    if (p && p->model.closed_solid()) best = std::move(p);
    else parts[k] = false;
  }
  return best;
}

// The wireframe cleaned (wireframe_cleanup.h) when the budget pays for its merges and splits: every pair of
// junctions, every edge against every junction.
std::optional<Wireframe> clean_within(const Wireframe& wf, const SurfaceOptions& o, WorkBudget& budget) {
  const long j = static_cast<long>(wf.junctions.size()), e = static_cast<long>(wf.edges.size());
  if (!budget.charge(j * (j - 1) / 2 + e * j, "cleaning")) return std::nullopt;
  return clean_wireframe(wf, o.merge_distance_m);
}

// The search once the graph is known to be searchable; `budget` pays for its steps.
SurfaceModel search(const Wireframe& wireframe, const SurfaceOptions& o, WorkBudget& budget) {
  // A model without a finished search: no faces, the budget's reason.
  const auto stopped = [&] {
    SurfaceModel m;
    m.reasons = {budget.reason()};
    return m;
  };
  // A finished model taken because a later attempt ran out of budget: an open one says so too.
  const auto keep = [&](Attempt& a) {
    if (budget.exhausted() && !a.model.closed_solid()) a.model.reasons.push_back(budget.reason());
    return std::move(a.model);
  };
  const std::optional<Wireframe> clean = clean_within(wireframe, o, budget);
  if (!clean) return stopped();
  const Wireframe& cleaned = *clean;
  Attempt first = build(cleaned, o, budget);
  if (first.stopped) return stopped();
  if (!o.complete_walls) return std::move(first.model);
  const std::optional<double> ground = ground_level(cleaned, o);
  if (first.model.closed_solid() && !(ground && o.prism_walls && floats_above(first.model, *ground, o))) return std::move(first.model);
  if (ground && o.prism_walls)
    if (std::optional<Attempt> prism = closed_prism(first, *ground, o, budget)) return std::move(prism->model);
  if (first.model.closed_solid() || budget.exhausted()) return keep(first);
  Wireframe extended = cleaned;
  const long cj = static_cast<long>(cleaned.junctions.size());
  long first_sides = 0;
  for (const SurfaceFace& f : first.model.faces) first_sides += static_cast<long>(f.ring.size());
  // The faces' sides, the edges, each eave corner's foot against the junctions.
  if (!budget.charge(first_sides + static_cast<long>(cleaned.edges.size()) + cj * cj, "walls down to the ground")) return keep(first);
  if (!complete_walls(extended, first, o)) return std::move(first.model);
  const std::optional<Wireframe> clean_extended = clean_within(extended, o, budget);
  if (!clean_extended) return keep(first);
  Attempt second = build(*clean_extended, o, budget);
  if (second.stopped) return keep(first);
  if (second.model.closed_solid()) return std::move(second.model);
  if (ground && o.prism_walls)
    if (std::optional<Attempt> prism = closed_prism(second, *ground, o, budget)) return std::move(prism->model);
  const bool take_second = !second.model.faces.empty() && second.defects() < first.defects();
  return keep(take_second ? second : first);
}

// The checks of the input, then the search; `budget` pays for it (one budget per building, whichever edge
// sets are searched).
SurfaceModel surfaces_within(const Wireframe& wireframe, const SurfaceOptions& o, WorkBudget& budget) {
  if (static_cast<int>(wireframe.edges.size()) > o.max_edges) {
    SurfaceModel m;
    m.reasons = {std::to_string(wireframe.edges.size()) + " edges: more than surfaces.max_edges (" + std::to_string(o.max_edges) +
                 "), not searched"};
    return m;
  }
  for (const auto& e : wireframe.edges)
    for (int j : e)
      if (j < 0 || j >= static_cast<int>(wireframe.junctions.size()) || !wireframe.junctions[j].allFinite()) {
        SurfaceModel m;  // the geometry below (sorting by height, plane fits) needs finite, existing junctions
        m.reasons = {"an edge has a junction that does not exist or is not finite: not searched"};
        return m;
      }
  return search(wireframe, o, budget);
}

}  // namespace

SurfaceModel surfaces_from_wireframe(const Wireframe& wireframe, const SurfaceOptions& o) {
  o.Check();
  WorkBudget budget(o.max_work_steps);
  SurfaceModel m = surfaces_within(wireframe, o, budget);
  m.work_steps = budget.used();
  return m;
}

SurfaceModel surfaces_from_wireframe(const Wireframe& wireframe, const std::vector<double>& scores, const SurfaceOptions& o) {
  if (scores.size() != wireframe.edges.size())
    throw std::invalid_argument("surfaces: " + std::to_string(scores.size()) + " edge scores for " +
                                std::to_string(wireframe.edges.size()) + " edges");
  o.Check();
  Wireframe confident;
  confident.junctions = wireframe.junctions;
  for (size_t e = 0; e < scores.size(); ++e)
    if (scores[e] >= o.min_edge_score) confident.edges.push_back(wireframe.edges[e]);
  WorkBudget budget(o.max_work_steps);  // one budget for both searches
  const auto finish = [&](SurfaceModel model) {
    model.work_steps = budget.used();
    return model;
  };
  SurfaceModel m = surfaces_within(confident.edges.size() == wireframe.edges.size() ? wireframe : confident, o, budget);
  if (confident.edges.size() == wireframe.edges.size() || m.closed_solid() || budget.exhausted()) return finish(std::move(m));
  SurfaceModel all = surfaces_within(wireframe, o, budget);
  if (all.closed_solid()) return finish(std::move(all));
  // The confident edges' faces stay; when the search of all the edges stopped at the budget, they say so.
  if (budget.exhausted()) m.reasons.push_back("all edges: " + budget.reason());
  return finish(std::move(m));
}

}  // namespace lc2wf

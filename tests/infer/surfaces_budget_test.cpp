// The face finder's work on large predicted graphs: the candidate planes (a grid over normal and offset) and
// the shell's face selection (a heap) give exactly what the scans over all clusters and all faces gave, and
// the work budget (SurfaceOptions::max_work_steps) bounds every search, counted in steps, not seconds: the
// largest predictions of the real test buildings finish within it, with faces or the budget's reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "dataset/geometry/wireframe_graph.h"
#include "infer/prediction_io.h"
#include "infer/surfaces/plane_candidates.h"
#include "infer/surfaces/plane_faces.h"
#include "infer/surfaces/shell_assembly.h"
#include "infer/surfaces/wireframe_cleanup.h"
#include "infer/surfaces/wireframe_surfaces.h"

namespace lc2wf {
namespace {

std::filesystem::path fixture(const std::string& name) {
  return std::filesystem::path(LC2WF_SOURCE_DIR) / "tests" / "data" / "surfaces" / name;
}

bool has_reason(const SurfaceModel& m, const std::string& part) {
  return std::any_of(m.reasons.begin(), m.reasons.end(), [&](const std::string& r) { return r.find(part) != std::string::npos; });
}

// The candidate planes as they were found before the grid: every pair of edges at a junction compared with
// every cluster so far (the first that matches takes it), each cluster refitted to the edges in its plane.
std::vector<CandidatePlane> candidate_planes_by_scan(const Wireframe& wf, const SurfaceOptions& o) {
  struct Cluster {
    Vec3 normal_sum;
    double offset_sum;
    int votes;
    Vec3 normal() const { return normal_sum.normalized(); }
    double offset() const { return offset_sum / votes; }
  };
  const int n = static_cast<int>(wf.junctions.size());
  const std::vector<std::vector<int>> incident = incident_edges(wf);
  const double min_sin = std::sin(o.min_edge_angle_deg * M_PI / 180);
  const double cos_merge = std::cos(o.plane_angle_deg * M_PI / 180);
  std::vector<Cluster> clusters;
  for (int j = 0; j < n; ++j)
    for (size_t x = 0; x < incident[j].size(); ++x)
      for (size_t y = x + 1; y < incident[j].size(); ++y) {
        const auto& ex = wf.edges[incident[j][x]];
        const auto& ey = wf.edges[incident[j][y]];
        const Vec3 dx = (wf.junctions[ex[0] == j ? ex[1] : ex[0]] - wf.junctions[j]).normalized();
        const Vec3 dy = (wf.junctions[ey[0] == j ? ey[1] : ey[0]] - wf.junctions[j]).normalized();
        Vec3 normal = dx.cross(dy);
        if (normal.norm() < min_sin) continue;
        normal.normalize();
        const double offset = normal.dot(wf.junctions[j]);
        bool added = false;
        for (Cluster& c : clusters) {
          const double cos = c.normal().dot(normal);
          if (std::abs(cos) < cos_merge) continue;
          const double sign = cos < 0 ? -1 : 1;
          if (std::abs(sign * offset - c.offset()) > o.plane_distance_m) continue;
          c.normal_sum += sign * normal;
          c.offset_sum += sign * offset;
          ++c.votes;
          added = true;
          break;
        }
        if (!added) clusters.push_back({normal, offset, 1});
      }
  std::stable_sort(clusters.begin(), clusters.end(), [](const Cluster& a, const Cluster& b) { return a.votes > b.votes; });
  std::vector<CandidatePlane> out;
  std::set<std::vector<int>> seen;
  for (const Cluster& c : clusters) {
    CandidatePlane cp;
    cp.plane.normal = c.normal();
    cp.plane.offset = c.offset();
    for (int pass = 0; pass < 2; ++pass) {
      cp.edges = edges_in_plane(wf, cp.plane, o.plane_distance_m);
      std::set<int> ids;
      for (int e : cp.edges) ids.insert({wf.edges[e][0], wf.edges[e][1]});
      if (ids.size() < 3) break;
      std::vector<Vec3> pts;
      for (int id : ids) pts.push_back(wf.junctions[id]);
      const Plane fitted = fit_plane(pts);
      if (plane_angle_deg(fitted.normal, cp.plane.normal) > 2 * o.plane_angle_deg) break;
      cp.plane = fitted;
    }
    cp.edges = edges_in_plane(wf, cp.plane, o.plane_distance_m);
    if (cp.edges.size() < 2 || !seen.insert(cp.edges).second) continue;
    out.push_back(std::move(cp));
  }
  return out;
}

// The face selection as it was before the heap: each round scans every kept face for the largest gain.
std::vector<int> select_by_scan(const std::vector<CandidateFace>& faces, const std::set<std::pair<int, int>>& added) {
  std::map<std::pair<int, int>, int> count;
  const auto side = [](const std::vector<int>& r, size_t i) {
    const int a = r[i], b = r[(i + 1) % r.size()];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  for (const auto& f : faces)
    for (size_t i = 0; i < f.ring.size(); ++i) ++count[side(f.ring, i)];
  std::vector<bool> kept(faces.size(), true);
  for (;;) {
    int best = -1, best_gain = 0;
    for (size_t f = faces.size(); f-- > 0;) {
      if (!kept[f]) continue;
      int g = 0;
      for (size_t i = 0; i < faces[f].ring.size(); ++i) {
        const auto s = side(faces[f].ring, i);
        g += count[s] >= 3 ? 1 : count[s] == 2 ? -1 : added.count(s) ? 1 : 0;
      }
      if (g > best_gain) best_gain = g, best = static_cast<int>(f);
    }
    if (best < 0) break;
    kept[best] = false;
    for (size_t i = 0; i < faces[best].ring.size(); ++i) --count[side(faces[best].ring, i)];
  }
  std::vector<int> out;
  for (size_t f = 0; f < faces.size(); ++f)
    if (kept[f]) out.push_back(static_cast<int>(f));
  return out;
}

void expect_same_planes(const std::vector<CandidatePlane>& a, const std::vector<CandidatePlane>& b, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(a.size(), b.size());
  for (size_t p = 0; p < a.size(); ++p) {
    EXPECT_EQ(a[p].edges, b[p].edges) << "plane " << p;
    EXPECT_EQ(a[p].plane.normal, b[p].plane.normal) << "plane " << p;  // bit for bit: the same arithmetic
    EXPECT_EQ(a[p].plane.offset, b[p].plane.offset) << "plane " << p;
  }
}

// Seeded noisy graphs: the real dense prediction with junctions moved and edges dropped, and random ones.
std::vector<Wireframe> test_graphs() {
  const Wireframe dense = clean_wireframe(read_prediction(fixture("dense_3dbag_665_edges.obj")).wireframe, 0.1);
  std::vector<Wireframe> out{dense};
  uint64_t state = 99;
  const auto next = [&] {  // splitmix64
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  const auto uniform = [&] { return static_cast<double>(next() >> 11) * 0x1.0p-53; };
  for (int trial = 0; trial < 12; ++trial) {
    Wireframe w;
    if (trial % 2 == 0) {
      w = dense;
      for (Vec3& j : w.junctions) j += Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5) * 0.3;
      std::vector<std::array<int, 2>> kept;
      for (const auto& e : w.edges)
        if (uniform() > 0.3) kept.push_back(e);
      w.edges = kept;
    } else {
      const int n = 20 + static_cast<int>(next() % 60);
      for (int i = 0; i < n; ++i) w.junctions.push_back(Vec3(20 * uniform(), 15 * uniform(), 10 * uniform()));
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
          if ((w.junctions[i] - w.junctions[j]).norm() < 8 && uniform() < 0.4) w.edges.push_back({i, j});
    }
    out.push_back(std::move(w));
  }
  return out;
}

TEST(SurfacesWork, CandidatePlanesFromTheGridEqualTheScanOverAllClusters) {
  const SurfaceOptions o;
  const std::vector<Wireframe> graphs = test_graphs();
  for (size_t g = 0; g < graphs.size(); ++g)
    expect_same_planes(candidate_planes(graphs[g], o), candidate_planes_by_scan(graphs[g], o), "graph " + std::to_string(g));
  // Wider and narrower merge settings change the grid's cells, not the planes.
  SurfaceOptions wide;
  wide.plane_angle_deg = 20;
  wide.plane_distance_m = 0.5;
  SurfaceOptions narrow;
  narrow.plane_angle_deg = 0.5;
  narrow.plane_distance_m = 0.01;
  for (const SurfaceOptions& x : {wide, narrow})
    expect_same_planes(candidate_planes(graphs[0], x), candidate_planes_by_scan(graphs[0], x), "other settings");
}

TEST(SurfacesWork, FaceSelectionWithAHeapEqualsTheScanOverAllFaces) {
  const SurfaceOptions o;
  int compared = 0;
  for (const Wireframe& w : test_graphs()) {
    std::vector<CandidateFace> faces;
    std::set<std::vector<int>> seen;
    const std::vector<CandidatePlane> planes = candidate_planes(w, o);
    for (size_t p = 0; p < planes.size(); ++p)
      for (std::vector<int>& ring : plane_cycles(w, planes[p], 0.025)) {
        std::vector<int> sorted = ring;
        std::sort(sorted.begin(), sorted.end());
        if (seen.insert(sorted).second) faces.push_back({std::move(ring), static_cast<int>(p)});
      }
    std::set<std::pair<int, int>> added;  // every fifth edge counts as added to close a gap
    for (size_t e = 0; e < w.edges.size(); e += 5) added.insert({w.edges[e][0], w.edges[e][1]});
    EXPECT_EQ(select_shell_faces(faces, added), select_by_scan(faces, added));
    compared += faces.size() > 100;
  }
  EXPECT_GT(compared, 0);  // some graphs have hundreds of candidate faces
}

// The largest prediction of the real test buildings (models of experiments/general-eval, 135 junctions,
// 665 edges, 67 of them confident; the building took 0.9 s before the grid and the heap): the search of all
// the edges stops at the budget, the confident edges' faces stay and say so.
TEST(SurfacesWork, TheDensestTestPredictionStopsAtTheBudgetAndKeepsItsConfidentFaces) {
  const ScoredWireframe p = read_prediction(fixture("dense_3dbag_665_edges.obj"));
  ASSERT_EQ(p.wireframe.edges.size(), 665u);
  const SurfaceOptions o;
  const SurfaceModel m = surfaces_from_wireframe(p.wireframe, p.edge_scores, o);
  EXPECT_LE(m.work_steps, o.max_work_steps);
  EXPECT_GT(m.work_steps, o.max_work_steps / 2);
  EXPECT_EQ(m.faces.size(), 6u);
  EXPECT_EQ(m.status, ShellStatus::kOpenSurfaces);
  EXPECT_TRUE(has_reason(m, "all edges: surfaces: work budget reached after ")) << m.reasons.back();
  EXPECT_TRUE(has_reason(m, "(surfaces.max_work_steps = 25000000) in "));

  // All its edges alone: the first shell (hundreds of open faces) is finished, the walls and the prism below
  // the roof are not; the last reason says so.
  const SurfaceModel all = surfaces_from_wireframe(p.wireframe, o);
  EXPECT_LE(all.work_steps, o.max_work_steps);
  EXPECT_EQ(all.status, ShellStatus::kOpenSurfaces);
  EXPECT_GT(all.faces.size(), 300u);
  ASSERT_FALSE(all.reasons.empty());
  EXPECT_EQ(all.reasons.back().rfind("surfaces: work budget reached after ", 0), 0u) << all.reasons.back();

  // With a larger budget the search finishes: hundreds of open faces, which is why the confident ones stay.
  SurfaceOptions unbounded = o;
  unbounded.max_work_steps = 200'000'000;
  const SurfaceModel finished = surfaces_from_wireframe(p.wireframe, unbounded);
  EXPECT_GT(finished.work_steps, o.max_work_steps);
  EXPECT_LT(finished.work_steps, 40'000'000);
  EXPECT_GT(finished.faces.size(), 300u);
  EXPECT_FALSE(has_reason(finished, "work budget"));
  const SurfaceModel scored = surfaces_from_wireframe(p.wireframe, p.edge_scores, unbounded);
  EXPECT_EQ(scored.faces.size(), m.faces.size());
  EXPECT_FALSE(has_reason(scored, "work budget"));
}

// A large prediction that all its edges close (101 junctions, 467 edges; the confident ones do not): within the
// budget, with room to spare.
TEST(SurfacesWork, ALargePredictionClosesWithinTheBudget) {
  const ScoredWireframe p = read_prediction(fixture("dense_vienna_467_edges.obj"));
  ASSERT_EQ(p.wireframe.edges.size(), 467u);
  const SurfaceModel m = surfaces_from_wireframe(p.wireframe, p.edge_scores);
  EXPECT_EQ(m.status, ShellStatus::kClosedSolid);
  EXPECT_EQ(m.faces.size(), 7u);
  EXPECT_TRUE(m.reasons.empty());
  EXPECT_GT(m.work_steps, 1'000'000);
  EXPECT_LT(m.work_steps, 22'000'000);  // 19.6 million when written
}

TEST(SurfacesWork, EveryBudgetIsKeptAndNamedWhereItRanOut) {
  const ScoredWireframe p = read_prediction(fixture("dense_vienna_467_edges.obj"));
  for (long budget : {1L, 1'000L, 100'000L, 1'000'000L, 5'000'000L}) {
    SCOPED_TRACE(budget);
    SurfaceOptions o;
    o.max_work_steps = budget;
    const SurfaceModel m = surfaces_from_wireframe(p.wireframe, p.edge_scores, o);
    EXPECT_LE(m.work_steps, budget);
    EXPECT_NE(m.status, ShellStatus::kClosedSolid);
    EXPECT_TRUE(has_reason(m, "surfaces: work budget reached after ")) << (m.reasons.empty() ? "" : m.reasons[0]);
  }
  // A hub: one junction with 1,999 edges spans two million candidate planes; the search does not start them.
  Wireframe hub;
  hub.junctions.push_back(Vec3::Zero());
  for (int i = 0; i < 1999; ++i) {
    const double a = 0.01 * i;
    hub.junctions.push_back(Vec3(10 * std::cos(a), 10 * std::sin(a), 0.004 * i));
    hub.edges.push_back({0, i + 1});
  }
  const SurfaceModel m = surfaces_from_wireframe(hub);
  EXPECT_EQ(m.status, ShellStatus::kNoFaces);
  EXPECT_LT(m.work_steps, SurfaceOptions{}.max_work_steps / 2);
  ASSERT_EQ(m.reasons.size(), 1u);
  EXPECT_NE(m.reasons[0].find("in candidate planes"), std::string::npos) << m.reasons[0];
}

TEST(SurfacesWork, TheBudgetMustBePositive) {
  SurfaceOptions o;
  o.max_work_steps = 0;
  EXPECT_THROW(
      try { o.Check(); } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("surfaces.max_work_steps"), std::string::npos);
        throw;
      },
      std::invalid_argument);
  EXPECT_THROW(surfaces_from_wireframe(Wireframe{}, o), std::invalid_argument);
}

// Hand-made buildings take a few thousand steps: the budget is no limit for them.
TEST(SurfacesWork, SmallBuildingsTakeFewSteps) {
  Wireframe box;
  box.junctions = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}, {0, 0, 2.5}, {4, 0, 2.5}, {4, 3, 2.5}, {0, 3, 2.5}};
  box.edges = {{0, 1}, {1, 2}, {2, 3}, {0, 3}, {4, 5}, {5, 6}, {6, 7}, {4, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  const SurfaceModel m = surfaces_from_wireframe(box);
  EXPECT_TRUE(m.closed_solid());
  EXPECT_GT(m.work_steps, 0);
  EXPECT_LT(m.work_steps, 20'000);
}

}  // namespace
}  // namespace lc2wf

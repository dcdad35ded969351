// The repair steps a building's polygon mesh goes through, one implementation each, shared by the
// procedural buildings (closed_mesh.h: exact geometry, micrometre tolerances) and the real LoD2 clean-up
// (lod2_cleanup.h: surveyed coordinates, millimetre to centimetre tolerances): welding, T-junctions made
// conforming, straight-edge vertices removed, unused vertices dropped. Faces are vertex-id rings.
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// The tolerances of the shared steps; the defaults suit exact (generated) geometry.
struct MeshRepairOptions {
  double weld_m = 1e-6;       // vertices closer than this are one vertex; a face thinner than this has no area
  double on_edge_m = 1e-6;    // a vertex this close to another face's edge (not to its ends) is inserted into it
  double collinear_m = 1e-6;  // a vertex with two neighbours this close to the segment between them is removed
  void Check() const;
};

using Ring = std::vector<int>;
using EdgeKey = std::pair<int, int>;  // undirected: (smaller id, larger id)
inline EdgeKey undirected_edge(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// Twice the area times the unit normal of a ring (robust for non-convex, slightly non-planar rings).
Vec3 newell_vector(const std::vector<Vec3>& vertices, const Ring& ring);
double longest_edge(const std::vector<Vec3>& vertices, const Ring& ring);
Vec3 ring_centroid(const std::vector<Vec3>& vertices, const Ring& ring);  // mean of its vertices
// Unique undirected edges of all faces (a repeated id is no edge).
std::set<EdgeKey> unique_edges(const std::vector<Ring>& faces);
// Repeated consecutive ids (and a closing repeat) removed; empty when fewer than 3 distinct ids remain.
Ring tidy_ring(const Ring& ring);

// Points -> vertex ids: a point within `tol` of an earlier vertex is that vertex (the lowest id if
// several); tol 0 welds exact repeats only. A hash grid of cell `tol` keeps it linear.
class VertexWelder {
 public:
  explicit VertexWelder(double tol) : tol_(tol) {}
  int add(const Vec3& p);
  // The ring's ids, tidied; empty when fewer than 3 distinct vertices or no area (every vertex within
  // tol of the line of its longest edge). Its points stay vertices either way.
  Ring add_ring(const std::vector<Vec3>& points);
  const std::vector<Vec3>& vertices() const { return vertices_; }
  std::vector<Vec3> take_vertices() { return std::move(vertices_); }

 private:
  double tol_;
  std::vector<Vec3> vertices_;
  std::unordered_map<unsigned long long, std::vector<int>> grid_;  // tol > 0
  std::map<std::array<double, 3>, int> exact_;                     // tol 0
};

// Ids of the vertices lying strictly inside segment (a, b): within `tol` of it and farther than `tol`
// from both ends (a vertex at an end is a near-duplicate, not a T), with their position t in (0, 1).
class EdgeInteriorIndex {
 public:
  EdgeInteriorIndex(const std::vector<Vec3>& vertices, std::vector<int> candidates, double tol);
  std::vector<std::pair<double, int>> inside(int a, int b) const;  // sorted by (t, id)

 private:
  const std::vector<Vec3>& vertices_;
  std::vector<int> ids_;   // by x
  std::vector<double> xs_;
  double tol_;
};

// Every vertex used by a face that lies strictly inside another face's edge (EdgeInteriorIndex) is
// inserted into that edge, in order along it. Returns the number of insertions.
int conform_t_junctions(const std::vector<Vec3>& vertices, std::vector<Ring>& faces, double tol);

// Vertices with exactly two neighbours in the edge graph, within `tol` of the segment between them, are
// removed from every face; of two neighbouring candidates one per pass (errors do not add up), repeated
// until none is left. Faces left with < 3 distinct vertices are erased; `kept_faces` gets, per remaining
// face, its index before the call. Returns how many vertices were removed.
int remove_collinear_vertices(const std::vector<Vec3>& vertices, std::vector<Ring>& faces, double tol,
                              std::vector<int>* kept_faces = nullptr);

// Vertices no face uses dropped, the rest renumbered in order of first use.
void drop_unused_vertices(std::vector<Vec3>& vertices, std::vector<Ring>& faces);

}  // namespace lc2wf

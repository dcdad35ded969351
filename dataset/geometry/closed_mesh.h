// Closed polygon meshes from faces given as point lists, and the checks a closed building mesh must pass:
// every edge used by exactly two faces in opposite directions, no vertex in the middle of another face's
// edge, no duplicate vertex, planar faces, outward orientation. The procedural buildings and the mesh
// augmentation are held to these.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct PointFace {
  std::vector<Vec3> points;  // counter-clockwise seen from outside
  FaceLabel label = FaceLabel::Wall;
};

// Welds points closer than `tol`, puts every vertex that lies on another face's edge into that face (so each
// edge is shared by exactly two faces), then drops vertices that only continue a straight edge (two
// neighbours, in line): the polygon edges left are the ones a person would draw.
PolyMesh mesh_from_faces(const std::vector<PointFace>& faces, double tol = 1e-6);

struct ClosedMeshReport {
  int edges_not_shared_by_two = 0;   // undirected edges used by one face or by more than two
  int edges_same_direction = 0;      // edges whose two faces walk them the same way (flipped face)
  int vertices_inside_edges = 0;     // T-junctions: a vertex strictly inside an edge of some face
  int duplicate_vertex_pairs = 0;    // vertex pairs closer than the tolerance
  int degenerate_faces = 0;          // < 3 vertices, or a vertex repeated within a face
  int unused_vertices = 0;
  double max_planarity_deviation = 0;
  double min_vertex_distance = 0;
  double volume = 0;                 // > 0 when the faces point outwards
  bool closed() const {
    return edges_not_shared_by_two == 0 && edges_same_direction == 0 && vertices_inside_edges == 0 &&
           duplicate_vertex_pairs == 0 && degenerate_faces == 0 && unused_vertices == 0 && volume > 0;
  }
};

ClosedMeshReport inspect_closed_mesh(const PolyMesh& mesh, double tol = 1e-6);

}  // namespace lc2wf

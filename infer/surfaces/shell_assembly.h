// From candidate faces to a shell: keep the faces a closed surface needs (each edge bounds two), merge
// the kept faces of one plane into one polygon, orient all faces consistently outward and move the vertices
// onto the planes of their faces.
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct CandidateFace {
  std::vector<int> ring;  // junction ids
  int plane = -1;         // candidate plane it was found in
};

// Indices of the candidates kept. Greedy: while some face's removal lowers the shell's defects, remove the
// face that lowers them most. An edge bounding three or more faces is a defect; so is a face's side that no
// other face shares when the side was added to close a gap (`added_edges`, (min, max) pairs); a side
// of the wireframe that bounds one face only (an open border) is none, so faces without neighbours survive.
std::vector<int> select_shell_faces(const std::vector<CandidateFace>& faces, const std::set<std::pair<int, int>>& added_edges);

// Kept faces sharing a side and lying in one plane (angle between their normals below `max_angle_deg`) become
// one polygon when their union is bounded by a single ring (a union with a hole stays in pieces).
std::vector<CandidateFace> merge_coplanar_faces(const std::vector<CandidateFace>& faces, const std::vector<Vec3>& vertices,
                                                double max_angle_deg);

// Reverses rings so every side shared by two faces is run in opposite directions by them, and each connected
// part encloses a positive volume (outward normals). False (with a reason) when no such orientation exists.
bool orient_faces(std::vector<std::vector<int>>& rings, const std::vector<Vec3>& vertices, std::vector<std::string>* reasons);

// Moves each vertex to the least-squares meeting point of its faces' planes (anchored weakly to where it is),
// refitting the planes in between: corners of three faces land where the three planes meet. A vertex whose
// meeting point lies farther than `max_move` (nearly parallel planes) goes to the mean of its projections.
void snap_vertices_to_planes(std::vector<Vec3>& vertices, const std::vector<std::vector<int>>& rings, double max_move,
                             int iterations = 3);

}  // namespace lc2wf

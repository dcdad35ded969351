// Wireframe edit distance (WED), per building. Two variants:
//  - release (the release's evaluation script, the paper's Table 2b): every predicted junction moves to its nearest GT
//    vertex at a cost of sqrt(distance in raw units)/raw_per_metre; GT vertices nobody moved to are "+vertex";
//    mapped predicted edges that hit a GT edge a second time are "−edge" (length between the mapped GT
//    vertices); GT edges never hit are "+edge". Spurious (non-GT or degenerate) mapped edges and surplus
//    predicted junctions cost nothing.
//  - strict: same nearest-GT mapping, but moves cost the Euclidean distance in metres, surplus predicted
//    junctions (several mapped to one GT vertex) count as "−vertex", and every mapped edge that is not the
//    first hit of a GT edge (duplicates, non-GT pairs, degenerate pairs) is a "−edge".
#pragma once

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct WedResult {
  int gt_vertices = 0;
  int gt_edges = 0;
  int pred_vertices = 0;
  int pred_edges = 0;
  double move = 0.0;         // metres; vertex translation cost ("+vertex Dist" column of Table 2b)
  int add_vertex = 0;        // GT vertices no predicted junction maps to
  int del_vertex = 0;        // strict only: predicted junctions beyond the first per GT vertex
  int add_edge = 0;          // GT edges never hit
  double add_edge_length = 0.0;  // metres
  int del_edge = 0;          // predicted edges deleted (release: duplicate GT hits only)
  double del_edge_length = 0.0;  // metres, measured between the mapped GT vertices

  int total_num() const { return add_vertex + del_vertex + add_edge + del_edge; }
  double total_dist() const { return move + add_edge_length + del_edge_length; }
};

// Release WED. Inputs in metres; raw_per_metre (20 for Roof-Image) reproduces the release's move cost
// sqrt(d_raw)/raw_per_metre. An empty GT maps nothing: every term is 0.
WedResult wed_release(const Wireframe& pred, const Wireframe& gt, double raw_per_metre = kRawUnitsPerMetre);

// Strict WED (metres). With an empty GT every predicted junction is a −vertex and every predicted edge a
// −edge charged its own length.
WedResult wed_strict(const Wireframe& pred, const Wireframe& gt);

}  // namespace lc2wf

// A test cloud with another extractor's statistics, made from a labelled cloud: every GT edge as a few
// long noisy fragments (as Line3D++'s clustered lines and LIMAP's tracks look), plus part of the cloud's
// own non-edge lines as clutter on the faces. The hard case for a model trained on many short fragments;
// used to measure how much the cloud augmentation (cloud_augmentation.h) buys.
#pragma once

#include <cstdint>

#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

struct LongFragmentOptions {
  int min_pieces = 2;             // fragments per GT edge, drawn uniformly in [min, max]
  int max_pieces = 5;
  double gap_fraction_max = 0.1;  // each cut leaves a gap of up to this fraction of the edge
  double noise_m = 0.02;          // isotropic Gaussian sigma per endpoint coordinate
  double clutter_keep = 0.5;      // fraction of the cloud's f = 0 lines kept
  double min_length_m = 0.1;      // shorter fragments are not made
  void Check() const;
};

// Deterministic for a seed. Labels: fragments carry their edge (make_edge_label), clutter keeps its own.
// Throws DataError naming the cloud when it has no labels or no GT wireframe.
LineCloud make_long_fragment_cloud(const LineCloud& labelled, const LongFragmentOptions& options, uint64_t seed);

}  // namespace lc2wf

// Training-time augmentation of a line cloud's statistics (not its pose, see augmentation.h): fuse the
// fragments of a GT edge into one long line, split lines into pieces, add noisy duplicates, drop lines
// and jitter endpoints. A model trained only on one extractor's clouds (ours: many short fragments)
// fails on clouds of long clustered lines (Line3D++, LIMAP, photo reconstructions); these draws cover
// both, and texture lines on the faces and the ground (surface_clutter.h) make them look like photo
// reconstructions. Labels (f, i1, d1, i2, d2) are carried to every new segment, so the usual patches follow.
#pragma once

#include <cstdint>

#include "dataset/geometry/line_cloud.h"
#include "dataset/synthetic/surface_clutter.h"

namespace lc2wf {

// Each strength is drawn per building uniformly in [0, max], so the model also sees near-clean clouds.
struct CloudAugmentOptions {
  double merge_prob_max = 0.6;      // per GT edge with >= 2 labelled fragments: fuse them into one line
  double split_prob_max = 0.3;      // per segment: cut into 2 or 3 pieces with small gaps
  double densify_prob_max = 0.2;    // per segment: add a duplicate (it gets its own endpoint noise)
  double drop_max = 0.3;            // fraction of segments removed
  double endpoint_noise_max_m = 0.03;  // isotropic Gaussian sigma per endpoint coordinate
  double min_length_m = 0.05;       // pieces shorter than this are not made
  // Texture lines, as a multiple of the cloud's segment count (photo clouds: ≈ 2.5 on faces, ≈ 3.5 on
  // the ground). 0 = none, which keeps the draws of the other steps as they were without these keys.
  double face_clutter_max = 0.0;
  double ground_clutter_max = 0.0;
  double clutter_length_max_m = 1.0;  // clutter lengths are uniform in [min_length_m, this]
  // Per building (not drawn in [0, max]): the cloud becomes a merged line map, as Line3D++ and LIMAP make
  // them (every GT edge's fragments fused), and is then cut as inference cuts such maps
  // (split_long_segments at kMergedMapPieceLength), so the model learns what --max-segment-length auto
  // gives it. 0 = never, which keeps every other draw as it was without this key.
  double merged_map_prob = 0.0;
  void Check() const;
};

// Deterministic for a seed. The result keeps the wireframe, cameras and units, has no 2D supports (the
// new segments have no observations), labels when the input had them, and at least one segment.
// f = 1 segments keep their GT edge (make_edge_label); a one-sided label keeps its junction only on a
// piece that still ends at that original endpoint. Throws DataError naming the cloud when it is empty.
LineCloud augment_cloud_statistics(const LineCloud& cloud, const CloudAugmentOptions& options, uint64_t seed);

}  // namespace lc2wf

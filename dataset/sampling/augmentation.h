// Per-building training augmentation (the release's `dataAug`): one uniform scale and one shift, applied
// jointly to segments, GT junctions and predicted junctions. The release draws the shift in network units
// (U(-0.1, 0.1) = +-1.331 m); here it is in metres. Optional rotation about the vertical axis.
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/network_frame.h"

namespace lc2wf {

class DataRng;

struct AugmentOptions {
  double scale_min = 0.8;
  double scale_max = 1.25;
  double shift_max_m = 0.1 * kReleaseStdRaw / kRawUnitsPerMetre;  // 0.1 network units
  bool rotate_z = false;
  void Check() const;
};

// p -> centre + scale * Rz(angle) * (p - centre) + shift, with centre = the network frame's centre so that
// in network units it is exactly y = s x + t.
struct Augmentation {
  double scale = 1.0;
  Vec3 shift_m = Vec3::Zero();
  double angle_rad = 0.0;
  Vec3 centre_m = Vec3::Zero();

  Vec3 apply(const Vec3& p) const;
  void apply(std::vector<Vec3>& points) const;
  void apply(std::vector<Segment3>& segments) const;
};

// Draw order: scale, shift x, y, z, then the angle (only when rotate_z).
Augmentation draw_augmentation(DataRng& rng, const AugmentOptions& options, const NetworkFrame& frame);

}  // namespace lc2wf

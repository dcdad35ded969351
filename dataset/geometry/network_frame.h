// Metres <-> network units. The release normalises raw coordinates with one global mean and a scalar
// std (MEAN = [0.12249484, -0.3440005, 70.5140106], STD = 266.2135032 raw); in metres that is
// centre = MEAN / kRawUnitsPerMetre and scale = STD / kRawUnitsPerMetre = 13.3107 m, the defaults here.
#pragma once

#include "dataset/geometry/geometry.h"

namespace lc2wf {

inline constexpr double kReleaseStdRaw = 266.2135032067564;  // the release's normalisation scale, raw units

struct NetworkFrame {
  Vec3 centre_m = Vec3(0.12249484, -0.3440005, 70.5140106) / kRawUnitsPerMetre;
  double scale_m = kReleaseStdRaw / kRawUnitsPerMetre;
  void Check() const;

  Vec3 to_network(const Vec3& metres) const { return (metres - centre_m) / scale_m; }
  Vec3 to_metres(const Vec3& network) const { return network * scale_m + centre_m; }
  // Lengths and offsets carry no centre.
  double length_to_network(double metres) const { return metres / scale_m; }
};

}  // namespace lc2wf

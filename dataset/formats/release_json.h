// Reader for the paper release's LineCloud JSON (`LineCloud_0130_P123/<name>.json`): `junc3DList` (2N x 3
// endpoints, consecutive pairs = segments), `label` (2N per-endpoint GT junction ids or -1),
// `objGTJunc3D` (V x 3), `line_idx` (E x 2). Raw units are converted to metres; the release frame is
// already recentred in x/y with z from the ground, so the default transform is a pure /20 scale.
#pragma once

#include <filesystem>
#include <string>

#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

struct ReleaseJsonOptions {
  double raw_per_metre = kRawUnitsPerMetre;
  Vec3 origin_raw = Vec3::Zero();
  void Check() const;
};

struct ReleaseJsonReport {
  int dropped_zero_length = 0;  // zero-length segments are dropped with their labels (the release keeps
                                // them at distance 1e5, where they are never selected)
};

// Labels: i1/i2 = the endpoint labels; f = both >= 0; d1/d2 = endpoint-to-junction distances in metres
// (-1 for a -1 label). The 2D data (`junc2DList`, `viewList`) is not imported: the JSON has no cameras.
LineCloud read_release_line_cloud(const std::filesystem::path& path, const ReleaseJsonOptions& options = {},
                                  ReleaseJsonReport* report = nullptr);
LineCloud parse_release_line_cloud(const std::string& text, const std::string& source_name,
                                   const ReleaseJsonOptions& options = {}, ReleaseJsonReport* report = nullptr);

}  // namespace lc2wf

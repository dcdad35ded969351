// GPS fixes as metres in a local east-north-up frame (WGS84 ellipsoid, tangent plane at the fixes' mean),
// so camera centres can be fitted to them by a similarity: x east, y north, z up.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/photo/exif_gps.h"

namespace lc2wf {

// One point per fix, same order; the origin is the tangent point (mean latitude / longitude / altitude).
// Fixes without altitude get the others' mean altitude.
std::vector<Vec3> local_enu(const std::vector<GpsFix>& fixes);

}  // namespace lc2wf

// The one JSON form of a camera, shared by line-cloud files, render outputs and the pose tools:
// {"K": [9 values, row-major], "R": [9 values, row-major], "t": [3], "width": W, "height": H}.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

nlohmann::json camera_to_json(const Camera& camera);
// Throws DataError naming `source` when a key is missing or has the wrong size or type, or the camera cannot
// project (non-finite values, focal length <= 0, R not a rotation, empty image size).
Camera camera_from_json(const nlohmann::json& j, const std::string& source);

}  // namespace lc2wf

#include "dataset/formats/camera_json.h"

#include <vector>

#include "core/util/json_number.h"
#include "dataset/formats/errors.h"

namespace lc2wf {

using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

nlohmann::json camera_to_json(const Camera& camera) {
  const RowMajor3 K = camera.K, R = camera.R;
  return {{"K", std::vector<double>(K.data(), K.data() + 9)},
          {"R", std::vector<double>(R.data(), R.data() + 9)},
          {"t", {camera.t.x(), camera.t.y(), camera.t.z()}},
          {"width", camera.width},
          {"height", camera.height}};
}

namespace {

// What makes a camera unusable for projection, or "" (checked on reading, so the error names the file and
// entry instead of a later stage's "view 0 has an invalid camera").
std::string camera_problem(const Camera& c) {
  if (!c.K.allFinite() || !c.R.allFinite() || !c.t.allFinite()) return "K, R or t holds a non-finite value";
  if (!(c.K(0, 0) > 0 && c.K(1, 1) > 0)) return "the focal lengths K[0] and K[4] must be > 0";
  if ((c.R * c.R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3 || !(c.R.determinant() > 0))
    return "R is not a rotation (orthonormal, determinant +1)";
  if (c.width <= 0 || c.height <= 0) return "width and height must be > 0";
  return "";
}

}  // namespace

Camera camera_from_json(const nlohmann::json& j, const std::string& source) {
  try {
    const auto K = json_exact_array<double>(j.at("K"), "camera K"), R = json_exact_array<double>(j.at("R"), "camera R");
    const auto t = json_exact_array<double>(j.at("t"), "camera t");
    if (K.size() != 9 || R.size() != 9 || t.size() != 3) throw DataError(source, "camera needs K[9], R[9], t[3]");
    Camera c;
    c.K = Eigen::Map<const RowMajor3>(K.data());
    c.R = Eigen::Map<const RowMajor3>(R.data());
    c.t = Vec3(t[0], t[1], t[2]);
    c.width = json_exact<int>(j.at("width"), "camera width");  // 2^32 + 640 must not become 640
    c.height = json_exact<int>(j.at("height"), "camera height");
    if (const std::string problem = camera_problem(c); !problem.empty()) throw DataError(source, "camera: " + problem);
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw DataError(source, std::string("malformed camera: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw DataError(source, std::string("malformed camera: ") + e.what());
  }
}

}  // namespace lc2wf

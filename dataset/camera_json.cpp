#include "dataset/camera_json.h"

#include <vector>

#include "core/util/json_number.h"
#include "dataset/errors.h"

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
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw DataError(source, std::string("malformed camera: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw DataError(source, std::string("malformed camera: ") + e.what());
  }
}

}  // namespace lc2wf

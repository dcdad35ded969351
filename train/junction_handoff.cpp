#include "train/junction_handoff.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/util/json_text.h"
#include "dataset/formats/errors.h"

namespace lc2wf {

namespace fs = std::filesystem;
constexpr const char* kFormat = "lc2wf-predicted-junctions";

fs::path predicted_junctions_path(const fs::path& dir, const std::string& name) { return dir / (name + ".json"); }

void write_predicted_junctions(const fs::path& dir, const std::string& name, const PredictedJunctions& p) {
  nlohmann::json positions = nlohmann::json::array();
  for (const Vec3& v : p.positions) positions.push_back({v.x(), v.y(), v.z()});
  nlohmann::json j = {{"format", kFormat}, {"version", 1},          {"name", name},
                      {"units", "metres"}, {"positions", positions}, {"confidences", p.confidence}};
  if (!p.offset_m.empty()) j["offsets"] = p.offset_m;  // optional: files of older hand-offs have none
  write_text_atomically(predicted_junctions_path(dir, name), json_text(j) + "\n");
}

PredictedJunctions read_predicted_junctions(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw DataError(path.string(), "cannot open predicted junctions");
  std::stringstream ss;
  ss << in.rdbuf();
  PredictedJunctions p;
  try {
    const nlohmann::json j = nlohmann::json::parse(ss.str());
    if (j.value("format", std::string()) != kFormat) throw DataError(path.string(), std::string("format is not '") + kFormat + "'");
    if (j.value("version", 0) != 1) throw DataError(path.string(), "unsupported version");
    for (const auto& v : j.at("positions")) {
      if (!v.is_array() || v.size() != 3) throw DataError(path.string(), "positions entries must be [x, y, z]");
      p.positions.emplace_back(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    }
    p.confidence = j.at("confidences").get<std::vector<double>>();
    if (j.contains("offsets")) p.offset_m = j.at("offsets").get<std::vector<double>>();
  } catch (const nlohmann::json::exception& e) {
    throw DataError(path.string(), std::string("malformed predicted junctions: ") + e.what());
  }
  if (p.positions.size() != p.confidence.size())
    throw DataError(path.string(), std::to_string(p.positions.size()) + " positions but " +
                                       std::to_string(p.confidence.size()) + " confidences");
  if (!p.offset_m.empty() && p.offset_m.size() != p.positions.size())
    throw DataError(path.string(), std::to_string(p.positions.size()) + " positions but " +
                                       std::to_string(p.offset_m.size()) + " offsets");
  for (double d : p.offset_m)
    if (!std::isfinite(d) || d < 0) throw DataError(path.string(), "offsets must be finite distances >= 0");
  for (size_t k = 0; k < p.positions.size(); ++k)
    if (!p.positions[k].allFinite() || !std::isfinite(p.confidence[k]) || p.confidence[k] < 0 || p.confidence[k] > 1)
      throw DataError(path.string(), "junction " + std::to_string(k) + " has a non-finite value or a confidence outside [0, 1]");
  return p;
}

}  // namespace lc2wf

#include "infer/prediction_io.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/mesh_io.h"

namespace lc2wf {
namespace {

constexpr const char* kFormat = "lc2wf-wireframe-scores";
constexpr int kVersion = 1;

std::optional<std::vector<double>> score_array(const nlohmann::json& j, const char* key, const std::string& source) {
  if (!j.contains(key)) return std::nullopt;
  const auto& a = j.at(key);
  if (!a.is_array()) throw DataError(source, std::string("'") + key + "' must be an array of numbers");
  std::vector<double> out;
  out.reserve(a.size());
  for (size_t k = 0; k < a.size(); ++k) {
    if (!a[k].is_number() || !std::isfinite(a[k].get<double>()))
      throw DataError(source, std::string("'") + key + "'[" + std::to_string(k) + "] is not a finite number");
    out.push_back(a[k].get<double>());
  }
  return out;
}

}  // namespace

std::string scores_json_string(const ScoredWireframe& prediction, const std::vector<std::string>& notes) {
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["junction_scores"] = prediction.junction_scores;
  j["edge_scores"] = prediction.edge_scores;
  j["notes"] = notes;
  return j.dump(1) + "\n";
}

PredictionScores parse_scores_json(const std::string& text, const std::string& source) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw DataError(source, "not valid JSON");
  if (!j.is_object()) throw DataError(source, "expected a JSON object");
  if (j.value("format", std::string()) != kFormat)
    throw DataError(source, std::string("'format' must be \"") + kFormat + "\"");
  if (!j.contains("version") || !j.at("version").is_number_integer() || j.at("version").get<int>() != kVersion)
    throw DataError(source, "'version' must be " + std::to_string(kVersion));
  if (!j.contains("junction_scores") && !j.contains("edge_scores"))
    throw DataError(source, "needs 'junction_scores' and/or 'edge_scores'");
  PredictionScores s;
  s.junction_scores = score_array(j, "junction_scores", source);
  s.edge_scores = score_array(j, "edge_scores", source);
  if (j.contains("notes")) {
    if (!j.at("notes").is_array()) throw DataError(source, "'notes' must be an array of strings");
    for (const auto& n : j.at("notes")) {
      if (!n.is_string()) throw DataError(source, "'notes' must be an array of strings");
      s.notes.push_back(n.get<std::string>());
    }
  }
  return s;
}

std::filesystem::path scores_path_for(const std::filesystem::path& obj) {
  std::filesystem::path p = obj;
  return p.replace_extension(".json");
}

ScoredWireframe read_prediction(const std::filesystem::path& obj_path, const UnitTransform* raw_units) {
  const ObjData obj = read_obj(obj_path);
  const std::string src = obj_path.string();
  if (!obj.mesh.faces.empty())
    throw DataError(src, "has 'f' faces; a predicted wireframe must list its edges as 'l' lines");
  Wireframe wf;
  wf.junctions = obj.mesh.vertices;
  if (raw_units)
    for (Vec3& p : wf.junctions) p = raw_units->to_metres(p);
  // Keep file order (and duplicates) so edge k lines up with edge_scores[k].
  for (const auto& l : obj.lines) wf.edges.push_back({std::min(l[0], l[1]), std::max(l[0], l[1])});

  ScoredWireframe out = ScoredWireframe::with_unit_scores(std::move(wf));
  const std::filesystem::path json = scores_path_for(obj_path);
  if (std::filesystem::exists(json)) {
    PredictionScores s = parse_scores_json(read_file(json), json.string());
    if (s.junction_scores) {
      if (s.junction_scores->size() != out.wireframe.junctions.size())
        throw DataError(json.string(), std::to_string(s.junction_scores->size()) + " junction scores but " + src +
                                           " has " + std::to_string(out.wireframe.junctions.size()) + " vertices");
      out.junction_scores = std::move(*s.junction_scores);
    }
    if (s.edge_scores) {
      if (s.edge_scores->size() != out.wireframe.edges.size())
        throw DataError(json.string(), std::to_string(s.edge_scores->size()) + " edge scores but " + src + " has " +
                                           std::to_string(out.wireframe.edges.size()) + " 'l' segments");
      out.edge_scores = std::move(*s.edge_scores);
    }
  }
  return out;
}

bool is_plain_file_name(const std::string& name) {
  // Anything else would write outside the folder or over another file.
  return !name.empty() && name != "." && name != ".." && name.find_first_of(std::string("/\0", 2)) == std::string::npos;
}

void write_prediction(const std::filesystem::path& dir, const std::string& name, const ScoredWireframe& prediction,
                      const std::vector<std::string>& notes, const UnitTransform* raw_units) {
  prediction.check("prediction " + name);
  if (!is_plain_file_name(name))
    throw std::invalid_argument("prediction name '" + name + "' is not a plain file name");
  std::filesystem::create_directories(dir);
  write_obj_wireframe(dir / (name + ".obj"), prediction.wireframe, raw_units);
  write_file_atomic(dir / (name + ".json"), scores_json_string(prediction, notes));
}

}  // namespace lc2wf

#include "dataset/formats/release_json.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/util/json_number.h"
#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"

namespace lc2wf {
namespace {

using Json = nlohmann::json;

std::vector<Vec3> read_points(const Json& j, const char* key, const std::string& src) {
  if (!j.contains(key)) throw DataError(src, std::string("missing key '") + key + "'");
  const Json& a = j.at(key);
  if (!a.is_array()) throw DataError(src, std::string("'") + key + "' must be an array");
  std::vector<Vec3> out;
  out.reserve(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    const Json& row = a[i];
    if (!row.is_array() || row.size() != 3) throw DataError(src, std::string("'") + key + "'[" + std::to_string(i) + "] must have 3 numbers");
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      if (!row[k].is_number()) throw DataError(src, std::string("'") + key + "'[" + std::to_string(i) + "] has a non-number");
      p[k] = row[k].get<double>();
    }
    if (!within_coordinate_limit(p)) throw DataError(src, std::string("'") + key + "'[" + std::to_string(i) + "] is not finite or beyond +-1e9");
    out.push_back(p);
  }
  return out;
}

// Labels may be stored flat (2N) or as (2N, 1).
std::vector<int> read_labels(const Json& j, const std::string& src) {
  if (!j.contains("label")) throw DataError(src, "missing key 'label'");
  std::vector<int> out;
  for (const Json& v : j.at("label")) {
    const Json& x = v.is_array() && v.size() == 1 ? v[0] : v;
    if (!x.is_number()) throw DataError(src, "'label' has a non-number");
    const double d = x.get<double>();
    if (d != std::floor(d) || d < -1 || d > 1e9) throw DataError(src, "'label' has a value that is not an id or -1");
    out.push_back(static_cast<int>(d));
  }
  return out;
}

}  // namespace

void ReleaseJsonOptions::Check() const {
  if (!(raw_per_metre > 0) || !std::isfinite(raw_per_metre)) throw std::invalid_argument("ReleaseJsonOptions.raw_per_metre must be > 0");
  if (!origin_raw.allFinite()) throw std::invalid_argument("ReleaseJsonOptions.origin_raw must be finite");
}

LineCloud parse_release_line_cloud(const std::string& text, const std::string& src, const ReleaseJsonOptions& o,
                                   ReleaseJsonReport* report) {
  o.Check();
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::exception& e) {
    throw DataError(src, std::string("malformed JSON: ") + e.what());
  }
  if (!j.is_object()) throw DataError(src, "top level must be an object");
  LineCloud c;
  c.name = std::filesystem::path(src).stem().string();
  c.units.raw_per_metre = o.raw_per_metre;
  c.units.origin_raw = o.origin_raw;
  try {
    const auto ends = read_points(j, "junc3DList", src);
    if (ends.size() % 2 != 0) throw DataError(src, "'junc3DList' has an odd number of endpoints (" + std::to_string(ends.size()) + ")");
    const auto labels = read_labels(j, src);
    if (labels.size() != ends.size()) {
      throw DataError(src, "'label' has " + std::to_string(labels.size()) + " entries for " + std::to_string(ends.size()) + " endpoints");
    }
    for (const auto& p : read_points(j, "objGTJunc3D", src)) c.wireframe.junctions.push_back(c.units.to_metres(p));
    const int nv = static_cast<int>(c.wireframe.junctions.size());
    if (!j.contains("line_idx")) throw DataError(src, "missing key 'line_idx'");
    for (const Json& e : j.at("line_idx")) {
      if (!e.is_array() || e.size() != 2) throw DataError(src, "'line_idx' rows must have 2 ids");
      const int a = json_exact<int>(e[0], "line_idx"), b = json_exact<int>(e[1], "line_idx");  // 2^32 must not wrap to 0
      if (a < 0 || b < 0 || a >= nv || b >= nv || a == b) {
        throw DataError(src, "'line_idx' edge (" + std::to_string(a) + ", " + std::to_string(b) + ") out of range for " +
                                 std::to_string(nv) + " junctions");
      }
      c.wireframe.edges.push_back({std::min(a, b), std::max(a, b)});
    }
    for (size_t k = 0; k < labels.size(); ++k) {
      if (labels[k] >= nv) throw DataError(src, "'label'[" + std::to_string(k) + "] = " + std::to_string(labels[k]) + " out of range for " + std::to_string(nv) + " junctions");
    }
    for (size_t k = 0; k < ends.size(); k += 2) {
      const Segment3 s{c.units.to_metres(ends[k]), c.units.to_metres(ends[k + 1])};
      if (!(s.length() > 0)) {
        if (report) ++report->dropped_zero_length;
        continue;
      }
      SegmentLabel l;
      l.i1 = labels[k];
      l.i2 = labels[k + 1];
      l.f = l.i1 >= 0 && l.i2 >= 0;
      l.d1 = l.i1 >= 0 ? (s.a - c.wireframe.junctions[l.i1]).norm() : -1.0;
      l.d2 = l.i2 >= 0 ? (s.b - c.wireframe.junctions[l.i2]).norm() : -1.0;
      c.segments.push_back(s);
      c.labels.push_back(l);
    }
  } catch (const Json::exception& e) {
    throw DataError(src, std::string("bad field: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw DataError(src, e.what());
  }
  validate_line_cloud(c, src);
  return c;
}

LineCloud read_release_line_cloud(const std::filesystem::path& path, const ReleaseJsonOptions& o, ReleaseJsonReport* report) {
  return parse_release_line_cloud(read_file(path), path.string(), o, report);
}

}  // namespace lc2wf

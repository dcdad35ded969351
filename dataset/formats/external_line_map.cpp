#include "dataset/formats/external_line_map.h"

#include <cmath>
#include <stdexcept>

#include "dataset/formats/errors.h"

namespace lc2wf {

void ExternalConversionOptions::Check() const {
  if (!(metres_per_unit > 0) || !std::isfinite(metres_per_unit))
    throw std::invalid_argument("ExternalConversionOptions.metres_per_unit must be a positive number");
}

LineCloud to_line_cloud(const ExternalLineMap& map, const std::string& name, const std::string& source,
                        const ExternalConversionOptions& options, ExternalConversionReport* report) {
  options.Check();
  ExternalConversionReport local;
  ExternalConversionReport& rep = report ? *report : local;
  LineCloud cloud;
  cloud.name = name;
  cloud.external_line_map = true;
  // Image ids are sparse and 1-based in COLMAP: views are numbered in ascending id order.
  std::map<long long, int> view_of;
  if (options.cameras) {
    for (const auto& [id, camera] : *options.cameras) {
      view_of[id] = static_cast<int>(cloud.cameras.size());
      cloud.cameras.push_back(camera);
    }
  }
  for (const ExternalLine& line : map.lines) {
    std::vector<Observation> obs;
    for (const ExternalSupport& s : line.supports) {
      const auto it = view_of.find(s.image_id);
      if (it == view_of.end()) {
        ++rep.supports_dropped;
        continue;
      }
      obs.push_back({it->second, s.seg});
    }
    rep.supports_kept += static_cast<long long>(obs.size());
    for (const Segment3& s : line.segments) {
      if (s.length() < 1e-9) {
        ++rep.zero_length_dropped;
        continue;
      }
      cloud.segments.push_back({s.a * options.metres_per_unit, s.b * options.metres_per_unit});
      if (options.cameras) cloud.support.push_back(obs);
    }
  }
  if (cloud.segments.empty()) throw DataError(source, "no 3D line segment");
  validate_line_cloud(cloud, source);
  return cloud;
}

}  // namespace lc2wf

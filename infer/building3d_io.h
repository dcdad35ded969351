// The Building3D-style section of metrics.md / metrics.json (definitions in infer/building3d_metric.h).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "infer/building3d_metric.h"

namespace lc2wf {

// The per-building counts with their building names, plus the pooled summary: what the outputs show.
struct Building3dReport {
  Building3dSummary summary;
  std::vector<std::string> names;         // one per per_building entry
  std::vector<Building3dCounts> per_building;
};

std::string building3d_markdown(const Building3dReport& report, const std::string& method);
nlohmann::json building3d_json(const Building3dReport& report);

}  // namespace lc2wf

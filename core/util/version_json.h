// The two fields that every JSON output describing a run carries (dataset summaries, metrics.json,
// report.json, the hand-off manifest): "lc2wf_version" and "commit". Header-only; users link nlohmann_json.
#pragma once

#include <nlohmann/json.hpp>

#include "core/util/version.h"

namespace lc2wf {

inline void add_version_fields(nlohmann::json& j) {
  j["lc2wf_version"] = lc2wf_version();
  j["commit"] = lc2wf_git_commit();
}

}  // namespace lc2wf

// Photos -> wireframe: images -> cameras (given or COLMAP) -> LSD -> our triangulation -> metric frame
// (scale, up, ground) -> junction + edge models -> post-processing. Every output is staged in the
// workspace and copied into OUT only after the last stage succeeded, so a failure leaves OUT untouched.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/cli.h"  // exit codes
#include "reconstruct/reconstruct_options.h"

namespace lc2wf {


struct ReconstructResult {
  int exit_code = kExitDone;
  nlohmann::json report;              // also written as OUT/report.json
  std::vector<std::string> warnings;  // why the run only partly succeeded
  std::vector<std::string> written;   // file names in OUT
  std::string workspace;              // where the intermediate files are (empty when removed)
};

// Throws StageError (nothing written to OUT) when a stage cannot go on, std::runtime_error for workspace
// or output I/O failures, std::invalid_argument for bad options.
ReconstructResult reconstruct(const ReconstructOptions& options);

}  // namespace lc2wf

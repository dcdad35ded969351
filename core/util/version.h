// Which lc2wf made an output: the release version and the git commit of the build, recorded in every file
// that describes a run (dataset summaries, metrics, checkpoints) and printed by every command's --version.
#pragma once

#include <string>

namespace lc2wf {

const char* lc2wf_version();     // e.g. "0.1.0"
const char* lc2wf_git_commit();  // `git describe --always --dirty` of the source tree at build time
std::string version_line();      // "0.1.0 (commit abc123def456)"

}  // namespace lc2wf

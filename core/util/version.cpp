#include "core/util/version.h"

#include "lc2wf_git_commit.h"  // generated at build time: LC2WF_GIT_COMMIT

namespace lc2wf {

const char* lc2wf_version() { return LC2WF_VERSION; }
const char* lc2wf_git_commit() { return LC2WF_GIT_COMMIT; }
std::string version_line() { return std::string(LC2WF_VERSION) + " (commit " + LC2WF_GIT_COMMIT + ")"; }

}  // namespace lc2wf

#include "harness/system_info.h"

#include "git_commit.h"  // generated at build time by cmake/git_commit.cmake

namespace sdfbench {

std::string git_commit() { return SDFBENCH_GIT_COMMIT; }

}  // namespace sdfbench

#pragma once
#include <string>

namespace sdfbench {

std::string git_commit();  // the commit sdfbench was built from, or "unknown"

}  // namespace sdfbench

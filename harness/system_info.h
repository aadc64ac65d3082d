#pragma once
#include <string>

namespace sdfbench {

std::string cpu_model();         // "AMD EPYC ..." from /proc/cpuinfo, or "unknown CPU"
unsigned hardware_threads();
std::string git_commit();        // the commit sdfbench was built from, or "unknown"

}  // namespace sdfbench

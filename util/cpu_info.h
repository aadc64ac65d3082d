#pragma once
// The machine's CPU, for device names and CSV rows (util/, so that renderers/ and harness/ both
// may use it).
#include <string>

namespace sdfbench {

std::string cpu_model();    // "AMD EPYC ..." from /proc/cpuinfo, or "unknown CPU"
unsigned hardware_threads();  // at least 1

}  // namespace sdfbench

#pragma once
// The running executable's GNU build ID (the linker's digest of its code and data): what ties a
// stored build to the exact program that made it.
#include <string>

namespace sdfbench {

// Lower-case hex of the main program's NT_GNU_BUILD_ID note; empty when it has none.
const std::string& executable_build_id();

}  // namespace sdfbench

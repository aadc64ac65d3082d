#pragma once
#include <string>

#include "scenes/scene.h"

namespace sdfbench {

// A scene named on the command line: a generator spec ("thesis:bunny:100[:seed]") or a JSON
// descriptor path.
Scene load_scene(const std::string& spec);

}  // namespace sdfbench

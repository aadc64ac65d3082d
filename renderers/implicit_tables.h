#pragma once
// A scene's implicit objects as the tables the shading program reads (implicit_trace.glsl).
#include <vector>

#include "renderers/shading/gpu_types.h"
#include "scenes/scene.h"

namespace sdfbench {

struct ImplicitTables {
  std::vector<shading::GpuImplicitObject> objects;
  std::vector<shading::GpuImplicitNode> nodes;  // every object's postfix nodes, concatenated
};

// Throws Error for a shape the kernels cannot evaluate (see implicit_bounds).
ImplicitTables make_implicit_tables(const Scene& scene);

}  // namespace sdfbench

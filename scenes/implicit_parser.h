#pragma once
#include <vector>

#include "scenes/implicit.h"
#include "scenes/json_field.h"

namespace sdfbench {

// An implicit object's "shape" tree (scenes/README.md, "implicits") as postfix nodes, checked
// against the kernels' limits; every rejection names the field.
std::vector<ImplicitNode> parse_implicit_shape(const JsonField& shape);

}  // namespace sdfbench

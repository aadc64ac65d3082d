#pragma once
// A toy backend that lives outside sdfbench (tests/toy_backend_test.cpp registers it at run time):
// every triangle of every instance tested for every ray, on the CPU. What a researcher's own
// backend looks like: a folder of code, one declaration, one parameter of its own (--toy-order).
#include "renderers/backend.h"

namespace sdfbench::toy {

BackendInfo toy_backend();

}  // namespace sdfbench::toy

#pragma once
// The sdfbench command line as a function: main() calls it, and so can a program that registers
// backends of its own first (renderers/backend_registry.h; tests/toy_backend_test.cpp).

namespace sdfbench {

// Parses the arguments, runs the command and returns the exit status; errors are one line on
// stderr ("sdfbench: error: ..."), as the commands promise.
int run_sdfbench(int argc, char** argv);

}  // namespace sdfbench

// sdfbench: reproduce and extend Menezes 2019 (hierarchical scene SDFs) against triangle
// ray tracers; see README.md.
#include "harness/cli_main.h"

int main(int argc, char** argv) { return sdfbench::run_sdfbench(argc, argv); }

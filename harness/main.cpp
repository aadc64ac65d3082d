// sdfbench: reproduce and extend Menezes 2019 (hierarchical scene SDFs) against triangle
// ray tracers; see README.md.
#include <iostream>

#include <CLI/CLI.hpp>

#include "harness/commands.h"
#include "scenes/error.h"

int main(int argc, char** argv) {
  CLI::App app{"sdfbench: a benchmark harness for ray tracing acceleration structures (SDF hash/octree vs triangles)"};
  app.set_version_flag("--version", std::string("sdfbench ") + SDFBENCH_VERSION);
  app.require_subcommand(1);
  sdfbench::register_info_command(app);
  sdfbench::register_render_command(app);
  sdfbench::register_compare_command(app);
  sdfbench::register_check_sdf_command(app);
  sdfbench::register_build_command(app);
  sdfbench::register_inspect_command(app);
  sdfbench::register_table_command(app);
  sdfbench::register_sweep_command(app);
  sdfbench::register_merge_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const sdfbench::CommandFailed& e) {
    return e.code;
  } catch (const sdfbench::Error& e) {
    std::cerr << "sdfbench: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "sdfbench: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}

#include "harness/cli_main.h"

#include <cstdio>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "harness/commands.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {

int run_sdfbench(int argc, char** argv) {
  CLI::App app{"sdfbench: a benchmark harness for ray tracing acceleration structures (SDF hash/octree vs triangles)"};
  app.set_version_flag("--version", std::string("sdfbench ") + SDFBENCH_VERSION);
  app.require_subcommand(1);
  sdfbench::register_info_command(app);
  sdfbench::register_backends_command(app);
  sdfbench::register_render_command(app);
  sdfbench::register_compare_command(app);
  sdfbench::register_check_sdf_command(app);
  sdfbench::register_build_command(app);
  sdfbench::register_inspect_command(app);
  sdfbench::register_table_command(app);
  sdfbench::register_sweep_command(app);
  sdfbench::register_merge_command(app);
  sdfbench::register_report_command(app);
  if (argc > 1 && argv[1][0] != '-') {  // CLI11 would only say "A subcommand is required"
    std::string known;
    bool found = false;
    for (const CLI::App* command : app.get_subcommands({})) {
      known += (known.empty() ? "" : ", ") + command->get_name();
      found = found || command->get_name() == argv[1];
    }
    if (!found) {
      std::cerr << "sdfbench: error: unknown command '" << argv[1] << "' (commands: " << known << ")\n";
      return 1;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Bad flags are user errors like any other: one line, exit 1 (CLI11's own codes vary).
    std::cerr << "sdfbench: error: " << e.what() << " (run with --help for usage)\n";
    return 1;
  } catch (const sdfbench::CommandFailed& e) {
    return e.code;
  } catch (const sdfbench::Error& e) {
    std::cerr << "sdfbench: error: " << sdfbench::printable(e.what()) << "\n";
    return 1;
  } catch (const std::length_error&) {  // a container asked for more than it can hold: a size, not a bug
    std::cerr << "sdfbench: error: out of memory: a structure or image size exceeds what can be allocated "
                 "(try a smaller --size, fewer objects or coarser SDF structures)\n";
    return 1;
  } catch (const std::bad_alloc&) {
    // Sizes the commands can estimate are refused up front; this is what slipped past them.
    std::cerr << "sdfbench: error: out of memory: the scene, its structures or the frame need more memory than "
                 "this machine can give (try a smaller --size, fewer objects or coarser SDF structures)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "sdfbench: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}

}  // namespace sdfbench

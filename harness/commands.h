#pragma once
#include <CLI/CLI.hpp>

namespace sdfbench {

// Each registers its subcommand and the callback that runs it.
void register_info_command(CLI::App& app);
void register_render_command(CLI::App& app);
void register_compare_command(CLI::App& app);
void register_check_sdf_command(CLI::App& app);
void register_build_command(CLI::App& app);
void register_inspect_command(CLI::App& app);
void register_table_command(CLI::App& app);
void register_sweep_command(CLI::App& app);
void register_merge_command(CLI::App& app);

}  // namespace sdfbench

namespace sdfbench {

// Thrown by a command that ran but must exit non-zero (e.g. images disagree); main returns `code`.
struct CommandFailed {
  int code;
};

}  // namespace sdfbench

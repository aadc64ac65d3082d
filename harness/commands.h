#pragma once
#include <CLI/CLI.hpp>

namespace sdfbench {

// Each registers its subcommand and the callback that runs it.
void register_info_command(CLI::App& app);
void register_backends_command(CLI::App& app);
void register_render_command(CLI::App& app);
void register_compare_command(CLI::App& app);
void register_check_sdf_command(CLI::App& app);
void register_build_command(CLI::App& app);
void register_inspect_command(CLI::App& app);
void register_table_command(CLI::App& app);
void register_sweep_command(CLI::App& app);
void register_merge_command(CLI::App& app);
void register_report_command(CLI::App& app);

}  // namespace sdfbench

namespace sdfbench {

// Thrown by a command that ran but must exit non-zero (e.g. images disagree); main returns `code`.
struct CommandFailed {
  int code;
};

// Exit statuses besides 0 (success) and 1 (an error that stopped the command): compare,
// check-sdf, table and sweep finished but some result is bad.
constexpr int kExitRowsDisagree = 2;  // images disagree with the reference (or were cut short)
constexpr int kExitRowsFailed = 4;    // table / sweep: some configurations failed (ERROR rows)

}  // namespace sdfbench

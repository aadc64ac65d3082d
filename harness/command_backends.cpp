// `sdfbench backends`: the registry (renderers/backend_registry.h) as text or JSON, so that
// scripts take their lists of backends and parameters from it rather than from copies.
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "harness/cli_common.h"
#include "harness/commands.h"
#include "harness/measurement.h"
#include "renderers/work_counters.h"

namespace sdfbench {
namespace {

const char* kind_name(ParamKind kind) {
  switch (kind) {
    case ParamKind::Integer: return "integer";
    case ParamKind::Real: return "real";
    case ParamKind::Choice: return "choice";
    case ParamKind::Flag: return "flag";
  }
  return "?";
}

nlohmann::json param_json(const ParamSpec& spec) {
  nlohmann::json p = {{"name", spec.name},       {"flag", flag_of(spec)},   {"kind", kind_name(spec.kind)},
                      {"default", spec.default_value}, {"help", spec.help}, {"group", spec.group},
                      {"values", describe_values(spec)}};
  if (!spec.choices.empty()) p["choices"] = spec.choices;
  if (spec.kind == ParamKind::Integer || spec.kind == ParamKind::Real) p["range"] = {spec.lo, spec.hi};
  if (!spec.only_when_param.empty()) p["only_when"] = {{spec.only_when_param, spec.only_when_value}};
  return p;
}

void print_json() {
  nlohmann::json out = {{"backends", nlohmann::json::array()}, {"default_table_backends", default_table_backends()}};
  for (const BackendInfo& b : backends()) {
    nlohmann::json entry = {{"name", b.name},
                            {"kind", to_string(b.kind)},
                            {"summary", b.summary},
                            {"device", b.vulkan ? "vulkan" : "cpu"},
                            {"counters", b.counters},
                            {"steps", b.steps},
                            {"stores_structure", b.stores_structure},
                            {"in_table", b.in_table},
                            {"params", nlohmann::json::array()},
                            {"partners", nlohmann::json::array()}};
    for (const ParamSpec& spec : b.params) entry["params"].push_back(param_json(spec));
    for (const BackendPartner& p : b.partners) entry["partners"].push_back({{"other", p.other}, {"what", p.what}});
    out["backends"].push_back(entry);
  }
  std::cout << out.dump(2) << "\n";
}

// The counters' CSV columns as docs/commands.md's CSV table lists them: "steps_per_ray, ...".
std::string counter_column_list() {
  std::string list;
  for (const std::string& column : counter_columns()) list += (list.empty() ? "" : ", ") + column;
  return list;
}

void print_text() {
  for (const BackendInfo& b : backends()) {
    std::cout << b.name << " (" << to_string(b.kind) << ", " << (b.vulkan ? "Vulkan" : "CPU") << (b.in_table ? "" : ", not in `table` by default")
              << "): " << b.summary << "\n";
    if (b.params.empty()) std::cout << "  parameters: none\n";
    for (const ParamSpec& spec : b.params)
      std::cout << "  " << flag_of(spec) << " = " << spec.default_value << "  (" << describe_values(spec) << ")\n";
  }
}

}  // namespace

void register_backends_command(CLI::App& app) {
  struct Args {
    bool json = false;
    std::string names;
    std::string counters_markdown;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("backends", "List the backends, what they support and the parameters each owns");
  cmd->add_flag("--json", args->json, "as JSON (names, kinds, parameters with defaults, ranges and choices; for scripts)");
  cmd->add_option("--names", args->names, "only the names, comma-separated: all, or table (those `table` runs by default)")
      ->check(CLI::IsMember({"all", "table"}));
  cmd->add_option("--counters-markdown", args->counters_markdown,
                  "docs/commands.md's generated counter text (harness/scripts/update_docs.sh writes it there): table "
                  "(the \"Counters\" table) or csv-columns (the counters' CSV columns, comma-separated)")
      ->check(CLI::IsMember({"table", "csv-columns"}));
  cmd->callback([args] {
    if (args->counters_markdown == "table") std::cout << counters_markdown();
    else if (args->counters_markdown == "csv-columns") std::cout << counter_column_list() << "\n";
    else if (args->names == "all") std::cout << backend_list() << "\n";
    else if (args->names == "table") std::cout << default_table_backends() << "\n";
    else if (args->json) print_json();
    else print_text();
  });
}

}  // namespace sdfbench

// `sdfbench table`: the thesis' FPS tables 6.1-6.3 over meshes x object counts, every backend
// beside them in the same mode, thesis values alongside; or the overlap table (issue 37): every
// backend over meshes x object counts x overlap k.
#include "harness/cli_common.h"
#include "harness/commands.h"
#include "harness/list_option.h"
#include "harness/overlap_axis.h"
#include "harness/run_options.h"
#include "harness/thesis_tables.h"
#include "scenes/mesh.h"
#include "scenes/mesh_resize.h"
#include "scenes/named_mesh.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct TableArgs {
  // objects and overlap: empty until run_table fills in the defaults of the table asked for
  std::string tables = "all", size, meshes = "bunny,teapot,monkey,sphere", objects, backends = default_table_backends(), mode,
              triangles, overlap;
  unsigned max_depth = 4;
  bool quick = false;
  RunOptions run;
  BackendOptions options;
};

bool is_overlap_table(const TableArgs& args) { return args.tables == kOverlapTable; }

// The thesis' tables asked for by --table; none for the overlap table, which runs alone.
std::vector<const ThesisTableConfig*> thesis_tables_of(const TableArgs& args) {
  std::vector<const ThesisTableConfig*> tables;
  if (is_overlap_table(args)) return tables;
  for (const std::string& id : args.tables == "all" ? std::vector<std::string>{"6.1", "6.2", "6.3"} : split_list(args.tables, "--table")) {
    if (id == kOverlapTable)
      throw Error("--table '" + args.tables + "': overlap is a table of its own (meshes x objects x --overlap); run it alone");
    const ThesisTableConfig* t = find_thesis_table(id);
    if (!t) throw Error("--table '" + id + "': expected 6.1, 6.2, 6.3, all or overlap");
    tables.push_back(t);
  }
  return tables;
}

std::vector<BenchConfig> table_plan(const TableArgs& args) {
  const bool overlap = is_overlap_table(args);
  const std::vector<const ThesisTableConfig*> tables = thesis_tables_of(args);
  if (!overlap && !args.overlap.empty()) throw Error("--overlap: only the overlap table reads it (--table overlap)");
  if (overlap && !args.triangles.empty())
    throw Error("--triangles: the overlap table's scenes (overlap:<mesh>:<count>:<k>) take the thesis meshes as they are");
  // The modes to run: each selected thesis table's own, or --mode (the overlap table: primary by default).
  std::vector<RenderMode> modes;
  if (overlap) modes.push_back(args.mode.empty() ? RenderMode::Primary : parse_mode_option(args.mode));
  for (const ThesisTableConfig* t : tables) {
    const RenderMode m = args.mode.empty() ? t->mode : parse_mode_option(args.mode);
    if (std::find(modes.begin(), modes.end(), m) == modes.end()) modes.push_back(m);
  }
  const std::vector<std::string> meshes = split_list(args.meshes, "--meshes");
  for (const std::string& mesh : meshes)
    if (!is_mesh_name(mesh)) throw Error("--meshes: '" + mesh + "' is not a mesh name (" + mesh_names_text() + ")");
    else if (!args.triangles.empty() && builtin_mesh_path(mesh).empty())
      throw Error("--meshes: '" + mesh + "' is a scan: --triangles resizes the thesis meshes only");
  // --triangles: every mesh at each size (thesis:<mesh>@<n>:<count>), the mesh-size axis.
  std::vector<std::string> mesh_specs;
  for (const std::string& mesh : meshes) {
    if (args.triangles.empty()) mesh_specs.push_back(mesh);
    for (const uint32_t n : args.triangles.empty() ? std::vector<uint32_t>{} : parse_list<uint32_t>(args.triangles, "--triangles")) {
      if (n < kMinResizedTriangles || n > kMaxResizedTriangles)
        throw Error("--triangles: " + std::to_string(n) + " is outside " + std::to_string(kMinResizedTriangles) + ".." +
                    std::to_string(kMaxResizedTriangles));
      mesh_specs.push_back(mesh + "@" + std::to_string(n));
    }
  }
  const std::vector<size_t> counts = parse_list<size_t>(args.objects, "--objects");
  for (size_t count : counts)
    if (count == 0) throw Error("--objects: counts must be >= 1");
  const std::vector<double> ks = overlap ? parse_overlap_list(args.overlap) : std::vector<double>{};
  const std::vector<std::string> backends = split_list(args.backends, "--backends");
  // Unknown names fail here, before hours of work; a device a backend cannot use (vk-rt without
  // ray tracing) makes its rows ERROR rows.
  for (const std::string& b : backends) check_backend_name(b);
  check_options_taken(args.options, backends);
  const ImageSize size = parse_size(args.size.empty() ? (args.quick ? "160x90" : "1280x720") : args.size);
  std::vector<std::pair<std::string, size_t>> axes = {{"--meshes x --triangles", mesh_specs.size()}, {"--objects", counts.size()}};
  if (overlap) axes.emplace_back("--overlap", ks.size());
  axes.insert(axes.end(), {{"modes", modes.size()}, {"--backends", backends.size()}});
  check_plan_size(axes);

  // The scenes in run order: a scene's rows follow one another, so the runner loads it once.
  std::vector<std::string> scenes;
  for (const std::string& mesh : mesh_specs)
    for (size_t count : counts) {
      if (!overlap) scenes.push_back("thesis:" + mesh + ":" + std::to_string(count));
      for (const double k : ks) scenes.push_back(overlap_scene(mesh, count, k));
    }
  std::vector<BenchConfig> plan;
  for (const std::string& scene : scenes)
    for (RenderMode mode : modes)
      for (const std::string& backend : backends) {
        BenchConfig c;
        if (overlap) c.table = kOverlapTable;
        for (const ThesisTableConfig* t : tables)
          if (t->backend == backend && t->mode == mode) c.table = t->id;
        c.scene = scene;
        c.backend = backend;
        c.mode = mode;
        c.size = size;
        c.max_depth = args.max_depth;
        c.options = args.options;
        plan.push_back(c);
      }
  return plan;
}

void run_table(TableArgs args) {
  const bool overlap = is_overlap_table(args);
  // The defaults of the table asked for; --quick: the README's first command, a few minutes on 2
  // cores (the overlap table's: one mesh, 100 objects, three k). Explicit flags still win.
  if (args.objects.empty()) args.objects = overlap ? (args.quick ? "100" : "1000") : (args.quick ? "1,10,100" : "1,10,100,1000");
  if (overlap && args.overlap.empty()) args.overlap = args.quick ? "1,4,16" : "1,2,4,8,16,32,50";
  if (args.quick) {
    if (args.meshes == "bunny,teapot,monkey,sphere") args.meshes = overlap ? "bunny" : "bunny,sphere";
    args.run.settings.frames = std::min(args.run.settings.frames, 3u);
    args.run.settings.budget_s = std::min(args.run.settings.budget_s, 20.0);
  }
  args.run.settings.check_size = parse_size(args.run.check_size);
  args.run.plan();  // a bad --shard fails before the plan is built
  std::vector<NamedPath> inputs;  // the thesis meshes the tables read
  for (const std::string& mesh : split_list(args.meshes, "--meshes")) inputs.push_back({"the thesis mesh", builtin_mesh_path(mesh)});
  run_and_report(table_plan(args), args.run, inputs);
}

}  // namespace

void register_table_command(CLI::App& app) {
  auto args = std::make_shared<TableArgs>();
  CLI::App* cmd = app.add_subcommand("table", "Reproduce the thesis' FPS tables 6.1-6.3 (meshes x object counts), every "
                                              "backend beside them, thesis values alongside; or the overlap table");
  cmd->add_option("--table", args->tables,
                  "6.1, 6.2, 6.3 (comma-separated) or all; or overlap: every backend on overlap:<mesh>:<count>:<k> scenes, "
                  "meshes x objects x --overlap, primary mode unless --mode")
      ->capture_default_str();
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT (default 1280x720, the thesis'; --quick: 160x90)");
  cmd->add_option("--meshes", args->meshes, "meshes: the thesis' four, or scans fetched by harness/scripts/fetch_scanned_meshes.sh (stanford-bunny, armadillo, dragon, elephant, bunny00)")->capture_default_str();
  cmd->add_option("--objects", args->objects, "object counts (default 1,10,100,1000; --table overlap: 1000; --quick: 1,10,100 and 100)");
  cmd->add_option("--overlap", args->overlap,
                  "--table overlap: the k of its scenes, boxes over each point, 1..64 (default 1,2,4,8,16,32,50; --quick: 1,4,16)");
  cmd->add_option("--triangles", args->triangles,
                  "mesh sizes: every mesh resized to each of these triangle counts (e.g. 1000,16000,256000; default: as they are)");
  cmd->add_option("--backends", args->backends, "backends run in every table's mode")->capture_default_str();
  cmd->add_option("--mode", args->mode, "run every table in this mode instead of the thesis' (whitted for 6.1/6.2, shadow for 6.3)");
  cmd->add_option("--max-depth", args->max_depth, "whitted recursion depth")->capture_default_str()->check(CLI::Range(0u, 16u));
  cmd->add_flag("--quick", args->quick,
                "small version (bunny and sphere, 1/10/100 objects, 160x90, 3 frames, 20 s budget; --table overlap: bunny, 100 "
                "objects, k 1,4,16): minutes on 2 cores");
  add_run_options(*cmd, args->run);
  add_backend_options(*cmd, args->options);
  cmd->callback([args] { run_table(*args); });
}

}  // namespace sdfbench

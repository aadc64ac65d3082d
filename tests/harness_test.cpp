// The harness around the backends: CSV reading/writing, the thesis table reader, markdown
// layout, sharding, merge checks, resume after a kill. Runs use the CPU backends at tiny sizes.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <thread>

#include "harness/benchmark_plan.h"
#include "harness/commands.h"
#include "harness/csv.h"
#include "harness/markdown_report.h"
#include "harness/measurement.h"
#include "harness/thesis_tables.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

TEST(Csv, EscapesAndParsesBackQuotesCommasAndLineBreaks) {
  const std::vector<std::string> fields = {"plain", "a,b", "say \"hi\"", "two\nlines", "", "llvmpipe (LLVM 15, 256 bits)"};
  EXPECT_EQ(csv_line({"a,b", "q\"q", "x"}), "\"a,b\",\"q\"\"q\",x\n");
  const CsvTable t = parse_csv(csv_line({"c1", "c2", "c3", "c4", "c5", "c6"}) + csv_line(fields), "test");
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.rows[0], fields);
  EXPECT_EQ(t.column("c4"), 3u);
  EXPECT_THROW(t.column("nope"), Error);
  // CRLF line ends and a missing final newline are accepted.
  const CsvTable crlf = parse_csv("a,b\r\n1,2\r\n3,4", "crlf");
  ASSERT_EQ(crlf.rows.size(), 2u);
  EXPECT_EQ(crlf.rows[1], (std::vector<std::string>{"3", "4"}));
}

TEST(Csv, MalformedFilesAreClearErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"a,b\n1,2,3\n", "row 1 has 3 fields"},
      {"a,b\n\"open,2\n", "unterminated quoted field"},
      {"a,b\n1,x\"y\n", "stray quote"},
      {"", "empty CSV"},
  };
  for (const auto& [text, words] : cases) {
    try {
      parse_csv(text, "bad.csv");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
}

TEST(Csv, WriteReadRoundTripThroughAFile) {
  test::TempDir dir;
  CsvTable t;
  t.columns = {"x", "y"};
  t.rows = {{"1", "a \"quoted\", value"}, {"2", ""}};
  write_csv(dir.path() / "t.csv", t);
  const CsvTable back = read_csv(dir.path() / "t.csv");
  EXPECT_EQ(back.columns, t.columns);
  EXPECT_EQ(back.rows, t.rows);
  EXPECT_THROW(write_csv(dir.path() / "missing" / "t.csv", t), Error);
}

TEST(MeasurementColumns, MatchTheDocumentedListAndFieldCount) {
  const std::vector<std::string>& c = measurement_columns();
  for (const char* required : {"scene", "mesh", "triangles", "objects", "backend", "mode", "width", "height", "hash_cell",
                               "octree_depth", "octree_min_objects", "octree_min_size", "lists", "mesh_cell", "cells_per_extent",
                               "hit", "max_steps", "hit_epsilon", "hit_footprint", "over_relax", "cell_bound", "storage_tables", "max_structure_mb", "cache", "on_bad_cache", "requested_frames", "warmup", "budget_s",
                               "reference", "requested_device", "whitted_passes", "validate", "frames", "ms_median", "ms_min", "ms_max",
                               "fps", "mrays_per_s", "steps_per_ray", "instance_evals_per_ray", "triangle_evals_per_ray",
                               "aabb_tests_per_ray", "triangle_tests_per_ray", "out_of_steps_per_ray",
                               "build_ms", "structure_bytes", "tree_sah", "tree_epo", "tree_nodes", "node_visits_per_ray", "hit_agreement", "id_agreement", "psnr", "budget_cut",
                               "device", "driver", "embree", "cpu", "threads", "commit"})
    EXPECT_NE(std::find(c.begin(), c.end(), required), c.end()) << required;
  EXPECT_EQ(to_csv_fields(Measurement{}).size(), c.size());
  EXPECT_EQ(std::set<std::string>(c.begin(), c.end()).size(), c.size()) << "duplicate column";
}

TEST(Shard, RoundRobinPartitionCoversEveryConfigurationOnce) {
  for (unsigned n = 1; n <= 5; ++n)
    for (size_t i = 0; i < 23; ++i) {
      int owners = 0;
      for (unsigned k = 1; k <= n; ++k) owners += in_shard(i, Shard{k, n});
      EXPECT_EQ(owners, 1) << i << " of " << n;
    }
  EXPECT_EQ(parse_shard("2/4").index, 2u);
  for (const char* bad : {"0/2", "3/2", "2", "a/b", "1/0", "1/2/3", ""}) EXPECT_THROW(parse_shard(bad), Error) << bad;
}

TEST(ThesisTables, ReadsTheCommittedCopy) {
  const ThesisTables t = ThesisTables::load_default();
  EXPECT_EQ(t.size(), 48u);  // 3 tables x 4 meshes x 4 object counts
  ASSERT_TRUE(t.find("6.1", "bunny", 1000));
  EXPECT_EQ(t.find("6.1", "bunny", 1000)->fps, 19);
  EXPECT_TRUE(t.find("6.3", "bunny", 1000)->upper_bound);
  EXPECT_FALSE(t.find("6.3", "monkey", 100)->upper_bound);
  EXPECT_FALSE(t.find("6.4", "bunny", 1));
  test::TempDir dir;
  EXPECT_THROW(ThesisTables::load(dir.write("bad.csv", "table,mesh,triangles,objects,fps,fps_upper_bound\n6.1,bunny,1,x,2,0\n")),
               Error);
  EXPECT_THROW(ThesisTables::load(dir.path() / "none.csv"), Error);
}

CsvTable rows_for_markdown() {
  CsvTable t;
  t.columns = measurement_columns();
  auto add = [&](const std::string& table, const std::string& mesh, size_t objects, const std::string& backend,
                 const std::string& mode, double fps, const std::string& agreement, bool cut) {
    Measurement m;
    m.table = table;
    m.mesh = mesh;
    m.objects = objects;
    m.backend = backend;
    m.mode = mode;
    m.width = 320;
    m.height = 180;
    m.fps = fps;
    m.agreement = agreement;
    m.budget_cut = cut;
    t.rows.push_back(to_csv_fields(m));
  };
  add("6.1", "bunny", 1, "sdf-octree", "whitted", 12.5, "ok", false);
  add("6.1", "bunny", 10, "sdf-octree", "whitted", 4.25, "DISAGREE: hit", false);
  add("6.3", "bunny", 1, "tri-aabb", "shadow", 2.5, "ok", false);
  add("6.3", "bunny", 10, "tri-aabb", "shadow", 0.5, "ok", true);
  add("6.1", "bunny", 100, "sdf-octree", "whitted", 2, "ok", false);
  add("6.3", "bunny", 100, "tri-aabb", "shadow", 40, "TRUNCATED: 200 pixels", false);
  add("", "bunny", 1, "embree", "shadow", 300, "reference", false);
  add("", "bunny", 1, "vk-rt", "whitted", 5, "ok", false);
  add("", "bunny", 10, "vk-rt", "whitted", 0, "ERROR: vk-rt: device 'x' lacks VK_KHR_ray_tracing_pipeline", false);
  return t;
}

TEST(MarkdownReport, LaysOutThesisTablesWithThesisValuesAndFlags) {
  const std::string md = markdown_report(rows_for_markdown(), ThesisTables::load_default());
  EXPECT_NE(md.find("### Table 6.1: sdf-octree, whitted (320x180)"), std::string::npos) << md;
  EXPECT_NE(md.find("| mesh \\ objects | 1 | 10 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| bunny | 12.5 (380) | 4.25 ✗ (100) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| bunny | 2.50 (9.0) | 0.500 † (1.0) | 40.0 ✂ ("), std::string::npos) << md;
  EXPECT_NE(md.find("✂ lavapipe's loop limit or a traversal's hard bound cut pixels short"), std::string::npos) << md;
  // Speed-up 6.1 / 6.3: 12.5 / 2.5 = 5x measured, 380 / 9 = 42x in the thesis.
  EXPECT_NE(md.find("| bunny | 5.00x (42x) | 8.50x (100x) | 0.05x ✂ ("), std::string::npos) << md;
  EXPECT_NE(md.find("### Every backend, shadow mode"), std::string::npos) << md;
  EXPECT_EQ(md.find("6.2"), std::string::npos) << "no rows for table 6.2, so no such table";
  // sdf-octree against vk-rt in whitted mode: 12.5 / 5; the ERROR row gives no ratio.
  EXPECT_NE(md.find("### sdf-octree against vk-rt (the thesis' structure against the driver's BVH), whitted mode"), std::string::npos) << md;
  EXPECT_NE(md.find("| bunny | 2.50x | – | – |"), std::string::npos) << md;
  EXPECT_EQ(md.find("driver's BVH, shadow mode"), std::string::npos) << "no vk-rt rows in shadow mode";
}

// A small sweep on the CPU backends (sdf-cpu vs the Embree reference), 4 configurations.
const std::string kSweep =
    "sweep --scene thesis:sphere:4 --backend sdf-cpu --size 32x18 --check-size 32x18 --frames 1 --warmup 0 "
    "--hash-cell 10,20 --octree-depth 0,1 --cells-per-extent 8";

std::set<std::string> configuration_keys(const CsvTable& t) {
  std::set<std::string> keys;
  for (const auto& row : t.rows) keys.insert(configuration_key(row, t.columns));
  return keys;
}

TEST(SweepCommand, ShardsMergeToTheUnshardedRows) {
  test::TempDir dir;
  const auto all = dir.path() / "all.csv", s1 = dir.path() / "s1.csv", s2 = dir.path() / "s2.csv",
             merged = dir.path() / "merged.csv";
  for (const auto& [args, path] : {std::pair{std::string(""), all}, {" --shard 1/2", s1}, {" --shard 2/2", s2}}) {
    const test::CommandResult r = test::run_sdfbench(kSweep + args + " --csv " + path.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const CsvTable full = read_csv(all);
  ASSERT_EQ(full.rows.size(), 4u);
  for (const auto& row : full.rows) {
    EXPECT_FALSE(row[full.column("build_ms")].empty());
    EXPECT_FALSE(row[full.column("hit_agreement")].empty());
    EXPECT_NE(std::stod(row[full.column("fps")]), 0.0);
  }
  EXPECT_EQ(read_csv(s1).rows.size(), 2u);
  const test::CommandResult m = test::run_sdfbench("merge " + s1.string() + " " + s2.string() + " --csv " + merged.string() +
                                                   " --markdown " + (dir.path() / "m.md").string());
  ASSERT_EQ(m.exit_code, 0) << m.output;
  const CsvTable joined = read_csv(merged);
  EXPECT_EQ(configuration_keys(joined), configuration_keys(full));
  for (size_t i = 0; i < joined.rows.size(); ++i)  // same order as the unsharded run
    EXPECT_EQ(joined.rows[i][joined.column("run_index")], full.rows[i][full.column("run_index")]);
  EXPECT_TRUE(fs::exists(dir.path() / "m.md"));

  // Overlapping inputs and foreign columns are refused.
  test::CommandResult bad = test::run_sdfbench("merge " + s1.string() + " " + all.string() + " --csv " + merged.string());
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("both measure"), std::string::npos) << bad.output;
  // A shard of another run (other --budget-s: same file name in a reused shard folder) is refused,
  // naming both files and the difference; all shards of one run share their run_id.
  const auto other = dir.path() / "other.csv";
  ASSERT_EQ(test::run_sdfbench(kSweep + " --budget-s 100 --shard 2/2 --csv " + other.string()).exit_code, 0);
  const CsvTable a = read_csv(s1), b = read_csv(s2), c = read_csv(other);
  EXPECT_EQ(a.rows[0][a.column("run_id")], b.rows[0][b.column("run_id")]);
  EXPECT_EQ(a.rows[0][a.column("run_id")], full.rows[0][full.column("run_id")]);
  EXPECT_NE(a.rows[0][a.column("run_id")], c.rows[0][c.column("run_id")]);
  bad = test::run_sdfbench("merge " + s1.string() + " " + other.string() + " --csv " + merged.string());
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  for (const std::string& words : {"'" + other.string() + "' is not from the run of '" + s1.string() + "'",
                                   std::string("budget_s '300' in '") + s1.string() + "', '100' in '" + other.string() + "'"})
    EXPECT_NE(bad.output.find(words), std::string::npos) << words << "\n" << bad.output;
  // ... unless asked to join several runs: then the files' rows one after the other.
  const test::CommandResult several =
      test::run_sdfbench("merge --several-runs " + other.string() + " " + s1.string() + " --csv " + merged.string());
  ASSERT_EQ(several.exit_code, 0) << several.output;
  const CsvTable both = read_csv(merged);
  ASSERT_EQ(both.rows.size(), c.rows.size() + a.rows.size());
  EXPECT_EQ(both.rows.front()[both.column("run_id")], c.rows[0][c.column("run_id")]);
  EXPECT_EQ(both.rows.back()[both.column("run_id")], a.rows[0][a.column("run_id")]);
  // A run_index near 2^64 stays in its file's place (the files were once ordered by a sum).
  CsvTable huge = c;
  huge.rows.resize(1);
  huge.rows[0][huge.column("run_index")] = "18446744073709551000";
  write_csv(dir.path() / "huge.csv", huge);
  ASSERT_EQ(test::run_sdfbench("merge --several-runs " + s1.string() + " " + (dir.path() / "huge.csv").string() + " --csv " +
                               merged.string()).exit_code, 0);
  const CsvTable ordered = read_csv(merged);
  EXPECT_EQ(ordered.rows.front()[ordered.column("run_id")], a.rows[0][a.column("run_id")]);
  EXPECT_EQ(ordered.rows.back()[ordered.column("run_index")], "18446744073709551000");
  const auto foreign = dir.write("foreign.csv", "a,b\n1,2\n");
  bad = test::run_sdfbench("merge " + s1.string() + " " + foreign.string() + " --csv " + merged.string());
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("other columns"), std::string::npos) << bad.output;
}

TEST(SweepCommand, KilledRunLeavesAValidCsvThatResumeCompletes) {
  test::TempDir dir;
  const fs::path csv = dir.path() / "run.csv";
  const std::string command = std::string(SDFBENCH_BINARY) + " " + kSweep + " --csv " + csv.string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", ("exec " + command + " >/dev/null 2>&1").c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Kill it as soon as the first row is in the file (or when it has finished).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int status = 0;
  bool exited = false;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    if (fs::exists(csv) && read_csv(csv).rows.size() >= 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!exited) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  const size_t rows_before = read_csv(csv).rows.size();  // parses: the file is never half-written
  EXPECT_GE(rows_before, 1u);
  const test::CommandResult resumed = test::run_sdfbench(kSweep + " --csv " + csv.string() + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const CsvTable done = read_csv(csv);
  EXPECT_EQ(done.rows.size(), 4u);
  EXPECT_EQ(configuration_keys(done).size(), 4u);
  // Only the CSV: the killed run's writes left no temporary file, and the lock is gone.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), {}), 1);
  if (rows_before < 4) {
    EXPECT_NE(resumed.output.find("already in"), std::string::npos) << resumed.output;
  }
}

// The sphere-tracing options are sweep axes, each row saying its values (issue 14).
TEST(SweepCommand, OverRelaxationAndCellBoundAreAxes) {
  test::TempDir dir;
  const auto csv = dir.path() / "options.csv";
  const test::CommandResult r = test::run_sdfbench(
      "sweep --scene thesis:sphere:4 --size 32x18 --check-size 32x18 --frames 1 --warmup 0 --cells-per-extent 8 "
      "--over-relax 1,1.5 --cell-bound 0,1 --csv " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable t = read_csv(csv);
  ASSERT_EQ(t.rows.size(), 4u);
  for (const auto& row : t.rows) EXPECT_EQ(row[t.column("storage_tables")], "0");
  std::set<std::pair<std::string, std::string>> seen;
  for (const auto& row : t.rows) {
    seen.emplace(row[t.column("over_relax")], row[t.column("cell_bound")]);
    EXPECT_EQ(row[t.column("agreement")], "ok") << row[t.column("over_relax")] << " " << row[t.column("cell_bound")];
  }
  EXPECT_EQ(seen, (std::set<std::pair<std::string, std::string>>{{"1", "0"}, {"1", "1"}, {"1.5", "0"}, {"1.5", "1"}}));
}

// Texel against storage buffers for the SDF tables is a sweep axis too (issue 17: a GPU may
// differ from lavapipe), each row saying which, the same work in both.
TEST(SweepCommand, StorageTablesAreAnAxis) {
  test::TempDir dir;
  const auto csv = dir.path() / "tables.csv";
  const test::CommandResult r = test::run_sdfbench(
      "sweep --scene thesis:sphere:4 --backend sdf-hash --size 32x18 --check-size 32x18 --frames 1 --warmup 0 "
      "--cells-per-extent 8 --storage-tables 0,1 --csv " + csv.string() + " --markdown " + (dir.path() / "t.md").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable t = read_csv(csv);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0][t.column("storage_tables")], "0");
  EXPECT_EQ(t.rows[1][t.column("storage_tables")], "1");
  EXPECT_EQ(t.rows[0][t.column("steps_per_ray")], t.rows[1][t.column("steps_per_ray")]);
  for (const auto& row : t.rows) EXPECT_EQ(row[t.column("agreement")], "ok");
  const test::CommandResult bad = test::run_sdfbench("sweep --scene thesis:sphere:1 --storage-tables 2");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("--storage-tables"), std::string::npos) << bad.output;
}

TEST(TableCommand, BadArgumentsAreClearErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"table --meshes cube", "not a mesh name"},
      {"table --objects 1,x", "--objects"},
      {"table --backends embree,raytracer", "unknown backend"},
      {"table --shard 3/2", "--shard"},
      {"table --size 0x10 --backends embree", "--size"},
      {"sweep --scene thesis:sphere:1 --backend embree --hash-cell 1,2",
       "--hash-cell is a parameter of sdf-hash, sdf-octree, sdf-bricks, sdf-cpu; --backend embree does not take it"},
      {"sweep --scene thesis:sphere:1 --backend sdf-cpu --hash-cell 0", "hash"},
      {"sweep --scene thesis:sphere:1 --over-relax 1,2.5", "--over-relax"},
      {"sweep --scene thesis:sphere:1 --cell-bound 0,2", "--cell-bound"},
      {"render --scene thesis:sphere:1 --backend sdf-cpu --cell-bound",
       "--cell-bound is a parameter of sdf-hash, sdf-octree; no backend of this run (sdf-cpu) takes it"},
      // Issue 27: values that are not finite, integers past their type, values listed twice, a
      // plan too large to build, a compare of nothing.
      {"sweep --scene thesis:sphere:1 --mesh-cell nan", "--mesh-cell: expected a number in [0, 1e+09], got 'nan'"},
      {"sweep --scene thesis:sphere:1 --hash-cell inf", "--hash-cell: expected a number in [1e-06, 1e+09], got 'inf'"},
      {"sweep --scene thesis:sphere:1 --octree-depth 5000000000", "--octree-depth: expected an integer in [0, 16], got '5000000000'"},
      {"table --objects 1,1", "--objects '1,1': '1' is listed twice"},
      {"table --backends embree,bvh,embree", "'embree' is listed twice"},
      {"sweep --scene thesis:sphere:1 --hash-cell 10,10.0", "'10.0' is listed twice (as '10')"},
      {"compare --scene thesis:sphere:1 --backends embree,embree", "'embree' is listed twice"},
      {"compare --scene thesis:sphere:1 --backends embree", "nothing to compare"},
      {"render --scene thesis:sphere:99999999999 --backend embree", "'99999999999' is out of range (at most 4294967295)"},
      // Issue 37: the overlap axis.
      {"table --overlap 1,2", "sdfbench: error: --overlap: only the overlap table reads it (--table overlap)"},
      {"table --table 6.1 --overlap 1,2", "--overlap: only the overlap table reads it"},
      {"table --table overlap,6.1", "--table 'overlap,6.1': overlap is a table of its own"},
      {"table --table overlap --overlap 0.5", "--overlap '0.5': 0.5 is outside [1, 64]"},
      {"table --table overlap --overlap 1,65", "--overlap '1,65': 65 is outside [1, 64]"},
      {"table --table overlap --overlap 2,2.0", "--overlap '2,2.0': '2.0' is listed twice (as '2')"},
      {"table --table overlap --overlap 1,x", "--overlap '1,x': 'x' is not a non-negative number"},
      {"table --table overlap --triangles 1000", "--triangles: the overlap table's scenes"},
      {"table --table overlap --meshes cube", "not a mesh name"},
      {"table --table 6.4", "--table '6.4': expected 6.1, 6.2, 6.3, all or overlap"},
      {"sweep --scene thesis:sphere:1 --backend sdf-cpu --overlap 1,2",
       "--overlap varies the k of an overlap:<mesh>:<count>:<k> scene; --scene 'thesis:sphere:1' is not one"},
      {"sweep --scene overlap:sphere:4:2 --backend sdf-cpu --overlap 1,70", "--overlap '1,70': 70 is outside [1, 64]"},
      {"sweep --scene overlap:cube:4:2 --backend sdf-cpu --overlap 1,2", "unknown mesh 'cube'"},
  };
  for (const auto& [args, words] : cases) {
    const test::CommandResult r = test::run_sdfbench(args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << args << "\n" << r.output;
  }
}

// Issue 36: a parameter that no backend of the run takes is an error naming the flag and the
// backends that take it, in every command, before anything is built.
TEST(BackendRegistry, AParameterNoBackendOfTheRunTakesIsAnError) {
  const std::pair<std::string, std::string> cases[] = {
      {"render --scene thesis:sphere:1 --backend embree --octree-depth 3",
       "--octree-depth is a parameter of sdf-octree, sdf-bricks, sdf-cpu; no backend of this run (embree) takes it"},
      {"table --backends bvh --voxels 64 --quick", "--voxels is a parameter of sdf-bricks; no backend of this run (bvh) takes it"},
      {"sweep --scene thesis:sphere:1 --backend sdf-global --lists exact,thesis",
       "--lists is a parameter of sdf-hash, sdf-octree, sdf-bricks, sdf-cpu; --backend sdf-global does not take it"},
      {"compare --scene thesis:sphere:1 --backends embree,bvh --global-voxel 0.5",
       "--global-voxel is a parameter of sdf-global; no backend of this run (embree, bvh) takes it"},
      {"build --scene thesis:sphere:1 --backend sdf-hash --octree-depth 2",
       "--octree-depth is a parameter of sdf-octree, sdf-bricks, sdf-cpu; no backend of this run (sdf-hash) takes it"},
      {"render --scene thesis:sphere:1 --backend bvh --cache x.sdfcache", "--cache stores the structures of"},
      {"render --scene thesis:sphere:1 --backend sdf-octree --hit field", "--hit field: sdf-octree takes exact or thesis"},
  };
  for (const auto& [args, words] : cases) {
    const test::CommandResult r = test::run_sdfbench(args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("sdfbench: error: " + words), std::string::npos) << args << "\n" << r.output;
  }
  // render says what it used, defaults included, as the CSV records it.
  const test::CommandResult used =
      test::run_sdfbench("render --scene thesis:sphere:1 --backend sdf-hash --size 16x9 --frames 1 --warmup 0 --max-steps 300");
  ASSERT_EQ(used.exit_code, 0) << used.output;
  EXPECT_NE(used.output.find("params   hash_cell=1 lists=exact mesh_cell=0 cells_per_extent=32"), std::string::npos) << used.output;
  EXPECT_NE(used.output.find("max_steps=300"), std::string::npos) << used.output;
}

// Issue 36: every declared parameter is a sweep axis (here two that the old sweep could not vary).
TEST(SweepCommand, VariesEveryDeclaredParameter) {
  test::TempDir dir;
  const std::string csv = (dir.path() / "s.csv").string();
  const test::CommandResult r = test::run_sdfbench(
      "sweep --scene thesis:sphere:4 --backend sdf-octree --lists exact,thesis --octree-min-size 1,2.5 --octree-depth 2 "
      "--size 32x18 --check-size 32x18 --frames 1 --warmup 0 --csv " + csv);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable t = read_csv(csv);
  ASSERT_EQ(t.rows.size(), 4u);
  std::set<std::string> seen;
  for (const auto& row : t.rows) {
    EXPECT_EQ(row[t.column("octree_depth")], "2");
    seen.insert(row[t.column("lists")] + "/" + row[t.column("octree_min_size")]);
  }
  EXPECT_EQ(seen, (std::set<std::string>{"exact/1", "exact/2.5", "thesis/1", "thesis/2.5"}));
}

// Issue 27, class 3: the plan's size is known before it is built; 25 M configurations are refused
// at once (in well under the minutes and gigabytes building them took), with the count and the limit.
TEST(SweepCommand, APlanTooLargeIsRefusedBeforeItIsBuilt) {
  std::string values;
  for (int i = 1; i <= 5000; ++i) values.append(i > 1 ? "," : "").append(std::to_string(i));
  const test::CommandResult r =
      test::run_sdfbench("sweep --scene thesis:sphere:1 --hash-cell " + values + " --octree-min-objects " + values);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("the plan lists 25000000 configurations (--hash-cell 5000 x --octree-min-objects 5000)"),
            std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the limit of 100000"), std::string::npos) << r.output;
  EXPECT_THROW(check_plan_size({{"a", size_t(1) << 40}, {"b", size_t(1) << 40}}), Error);  // no overflow to a small product
  EXPECT_NO_THROW(check_plan_size({{"a", 1000}, {"b", 100}}));
}

// Issue 27, classes 6, 9 and 13: failed rows make the exit status 4; --resume runs them again
// (and says so); the structure cap is part of the key; an empty shard still writes its CSV.
TEST(SweepCommand, FailedRowsExitNonZeroAndResumeRetriesThem) {
  test::TempDir dir;
  const std::string csv = (dir.path() / "s.csv").string();
  // The ray-tracing extension hidden: the vk-rt row is an ERROR row.
  const test::CommandResult hidden = test::run_shell("SDFBENCH_VULKAN_HIDE_EXTENSIONS=VK_KHR_ray_tracing_pipeline " +
                                                     std::string(SDFBENCH_BINARY) + " table --table 6.3 --meshes sphere "
                                                     "--objects 1 --backends embree,vk-rt --size 32x18 --check-size 32x18 "
                                                     "--frames 1 --warmup 0 --csv " + csv + " 2>&1");
  EXPECT_EQ(hidden.exit_code, kExitRowsFailed) << hidden.output;
  EXPECT_NE(hidden.output.find("1 of 2 configurations failed (ERROR rows in '" + csv + "'; --resume runs them again)"),
            std::string::npos) << hidden.output;
  const test::CommandResult resumed = test::run_sdfbench("table --table 6.3 --meshes sphere --objects 1 --backends embree,vk-rt "
                                                         "--size 32x18 --check-size 32x18 --frames 1 --warmup 0 --resume --csv " + csv);
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resume: retrying 1 configuration(s) that failed before"), std::string::npos) << resumed.output;
  const CsvTable rows = read_csv(csv);
  ASSERT_EQ(rows.rows.size(), 2u);
  for (const auto& row : rows.rows) EXPECT_EQ(row[rows.column("agreement")].rfind("ERROR", 0), std::string::npos);

  // Shard 3 of 5 of a 2-configuration table has nothing to run: its CSV is the header alone.
  const std::string empty = (dir.path() / "empty.csv").string();
  const test::CommandResult shard = test::run_sdfbench("table --table 6.3 --meshes sphere --objects 1 --backends embree,tri-aabb "
                                                       "--size 32x18 --frames 1 --shard 3/5 --csv " + empty);
  EXPECT_EQ(shard.exit_code, 0) << shard.output;
  EXPECT_EQ(read_csv(empty).rows.size(), 0u);
  EXPECT_EQ(read_csv(empty).columns, measurement_columns());

  const std::vector<std::string>& key = configuration_key_columns();
  for (const char* column : {"max_structure_mb", "cache", "on_bad_cache"})
    EXPECT_NE(std::find(key.begin(), key.end(), column), key.end()) << column;
}

}  // namespace
}  // namespace sdfbench

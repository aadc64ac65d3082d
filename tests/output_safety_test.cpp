// Output files and result files under a hostile user (issue 11, classes 1 and 5): planted
// symlinks, special files in place of an output, killed writes, concurrent writers, resumed and
// merged CSVs of other runs. Every CLI run has a timeout, so a hang fails instead of hanging.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "harness/csv.h"
#include "harness/measurement.h"
#include "renderers/backend_registry.h"
#include "scenes/mesh.h"
#include "tests/test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

using test::run_shell;

test::CommandResult sdfbench(const std::string& args) { return run_shell(std::string("exec ") + SDFBENCH_BINARY + " " + args); }

// Exit 1 with one "sdfbench: error:" line holding every one of `words`.
void expect_user_error(const std::string& args, const std::vector<std::string>& words) {
  const test::CommandResult r = sdfbench(args);
  EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;  // 124: it hung
  EXPECT_NE(r.output.find("sdfbench: error: "), std::string::npos) << args << "\n" << r.output;
  for (const std::string& w : words) EXPECT_NE(r.output.find(w), std::string::npos) << w << "\n" << args << "\n" << r.output;
}
void expect_user_error(const std::string& args, const std::string& words) { expect_user_error(args, std::vector{words}); }

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every name in `dir` (hidden ones included) with its type and, for files, contents: equal
// snapshots mean nothing there changed.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> entries;
  for (const auto& e : fs::directory_iterator(dir)) {
    const fs::path p = e.path();
    std::string state;
    if (fs::is_symlink(fs::symlink_status(p))) state = "link -> " + fs::read_symlink(p).string();
    else if (fs::is_fifo(fs::symlink_status(p))) state = "fifo";
    else if (fs::is_directory(fs::symlink_status(p))) state = "dir";
    else state = "file: " + read_file(p);
    entries[p.filename().string()] = state;
  }
  return entries;
}

std::set<std::string> names(const fs::path& dir) {
  std::set<std::string> n;
  for (const auto& e : fs::directory_iterator(dir)) n.insert(e.path().filename().string());
  return n;
}

std::span<const std::byte> bytes_of(const std::string& text) { return std::as_bytes(std::span(text.data(), text.size())); }

const std::string kRender = "render --backend embree --scene thesis:sphere:5 --size 32x18 --frames 1 --warmup 0";

// Two configurations of the sdf-cpu backend (well under a second), with `changes` ("--frames 2")
// replacing the flags of the same names.
std::string sweep(const std::vector<std::pair<std::string, std::string>>& changes = {}) {
  std::vector<std::pair<std::string, std::string>> flags = {
      {"--scene", "thesis:sphere:4"}, {"--backend", "sdf-cpu"}, {"--size", "32x18"}, {"--check-size", "32x18"},
      {"--frames", "1"}, {"--warmup", "0"}, {"--hash-cell", "10"}, {"--octree-depth", "0,1"}, {"--cells-per-extent", "8"}};
  for (const auto& change : changes) {
    auto it = std::find_if(flags.begin(), flags.end(), [&](const auto& f) { return f.first == change.first; });
    if (it != flags.end()) it->second = change.second;
    else flags.push_back(change);
  }
  std::string args = "sweep";
  for (const auto& [flag, value] : flags) args += " " + flag + " " + value;
  return args;
}
const std::string kSweep = sweep();

// Class 1: a symlink at the target is refused, for every kind of output; the file it points at
// (outside the output directory) and the link itself stay as they were.
TEST(OutputSafety, SymlinkAtTheTargetIsRefusedAndWhatItPointsAtUntouched) {
  test::TempDir outside, dir;
  const fs::path secret = outside.write("secret.txt", "precious");
  const fs::path csv = dir.path() / "run.csv";
  const test::TempDir inputs;
  const fs::path input = inputs.write("in.csv", csv_line(measurement_columns()));
  for (const char* name : {"a.png", "a.exr", "h.png", "run.csv", "run.md", "cache.sdfc"})
    fs::create_symlink(secret, dir.path() / name);
  const auto before = snapshot(dir.path());
  const std::string d = dir.path().string() + "/";
  const std::pair<std::string, std::string> cases[] = {
      {kRender + " --out " + d + "a.png", "--out"},
      {kRender + " --aov " + d + "a.exr", "--aov"},
      {"render --backend sdf-cpu --scene thesis:sphere:1 --size 8x8 --frames 1 --warmup 0 --heatmap " + d + "h.png", "--heatmap"},
      {kSweep + " --csv " + d + "run.csv", "--csv"},
      {kSweep + " --csv " + d + "run2.csv --markdown " + d + "run.md", "--markdown"},
      {"merge " + input.string() + " --csv " + d + "run.csv", "--csv"},
      {"build --scene thesis:sphere:1 --cells-per-extent 4 --cache " + d + "cache.sdfc", "--cache"},
  };
  for (const auto& [args, option] : cases)
    expect_user_error(args, {option + " '" + d, "exists and is not a regular file (a symlink)"});
  EXPECT_EQ(read_file(secret), "precious");
  EXPECT_EQ(snapshot(dir.path()), before);
}

// Class 1: symlinks planted where the old code put its temporary files (".<stem>.tmp<pid><ext>",
// guessable) are never written through; the output is a new regular file beside them.
TEST(OutputSafety, SymlinksPlantedAtGuessableTempNamesAreNeverFollowed) {
  test::TempDir outside, dir;
  const fs::path secret = outside.write("secret.txt", "precious");
  const std::string d = dir.path().string() + "/";
  // `exec` keeps the shell's pid ($$), so the links sit at the names that process would use.
  std::string plant;
  for (const char* name : {".a.tmp$$.png", ".a.tmp$$.exr", ".run.tmp$$.csv", ".run.tmp$$.md"})
    plant += "ln -s " + secret.string() + " " + d + name + "; ";
  test::CommandResult r = run_shell(plant + "exec " + SDFBENCH_BINARY + " " + kRender + " --out " + d + "a.png --aov " + d + "a.exr");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_shell(plant + "exec " + SDFBENCH_BINARY + " " + kSweep + " --csv " + d + "run.csv --markdown " + d + "run.md");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_file(secret), "precious");
  for (const char* out : {"a.png", "a.exr", "run.csv", "run.md"}) {
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir.path() / out))) << out;
    EXPECT_GT(fs::file_size(dir.path() / out), 100u) << out;
  }
  size_t links = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) links += fs::is_symlink(e.symlink_status());
  EXPECT_EQ(links, 8u);  // the planted ones, untouched: 2 runs x 4 names
  EXPECT_EQ(names(dir.path()).size(), 12u) << "a temporary file or lock was left behind";

  // The same in-process, at this process's old temp name.
  const fs::path target = dir.path() / "t.csv";
  fs::create_symlink(secret, dir.path() / (".t.tmp" + std::to_string(::getpid()) + ".csv"));
  write_file_atomically(target, bytes_of("a,b\n"));
  EXPECT_EQ(read_file(target), "a,b\n");
  EXPECT_EQ(read_file(secret), "precious");
}

// Class 1: --csv /dev/null (and any FIFO, device or directory) is refused, never replaced. Run
// as root here, so a FIFO and a symlink to a file stand in for /dev/null.
TEST(OutputSafety, SpecialFilesInPlaceOfAnOutputAreRefusedUntouched) {
  test::TempDir dir;
  const std::string d = dir.path().string() + "/";
  for (const char* fifo : {"f.png", "f.exr", "f.csv", "f.md", "f.sdfc"}) ASSERT_EQ(::mkfifo((d + fifo).c_str(), 0644), 0);
  fs::create_directory(dir.path() / "sub.png");
  const auto before = snapshot(dir.path());
  const test::TempDir inputs;
  const fs::path input = inputs.write("in.csv", csv_line(measurement_columns()));
  const std::pair<std::string, std::string> cases[] = {
      {kRender + " --out " + d + "f.png", "(a FIFO)"},
      {kRender + " --aov " + d + "f.exr", "(a FIFO)"},
      {kSweep + " --csv " + d + "f.csv", "--csv '" + d + "f.csv' exists and is not a regular file (a FIFO)"},
      {kSweep + " --csv " + d + "f.csv --resume", "(a FIFO)"},
      {kSweep + " --csv " + d + "ok.csv --markdown " + d + "f.md", "(a FIFO)"},
      {"merge " + input.string() + " --csv " + d + "f.csv", "(a FIFO)"},
      {"build --scene thesis:sphere:1 --cells-per-extent 4 --cache " + d + "f.sdfc", "(a FIFO)"},
      {kRender + " --out " + d + "sub.png", "is a directory"},
      {kRender + " --out " + d, "names a directory"},
  };
  for (const auto& [args, words] : cases) expect_user_error(args, words);
  EXPECT_EQ(snapshot(dir.path()), before);
  for (const char* fifo : {"f.png", "f.exr", "f.csv", "f.md", "f.sdfc"}) EXPECT_TRUE(fs::is_fifo(dir.path() / fifo)) << fifo;

  // The check right before the rename: a FIFO that appears after the early check.
  EXPECT_THROW(write_file_atomically(dir.path() / "f.csv", bytes_of("x")), Error);
  EXPECT_THROW(write_file_atomically(dir.path() / "sub.png", bytes_of("x")), Error);
  EXPECT_EQ(snapshot(dir.path()), before);
}

// Class 5: no temporary file after a run, after a failed write, or after a write killed half way.
TEST(OutputSafety, NoTemporaryFileIsLeftBehind) {
  test::TempDir dir;
  const std::string d = dir.path().string() + "/";
  test::CommandResult r = sdfbench(kRender + " --out " + d + "a.png --aov " + d + "a.exr");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = sdfbench(kSweep + " --csv " + d + "run.csv --markdown " + d + "run.md");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = sdfbench(kSweep + " --csv " + d + "run.csv --resume");  // replaces the CSV with itself
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(names(dir.path()), (std::set<std::string>{"a.png", "a.exr", "run.csv", "run.md"}));

  // Failed writes: the directory is gone, the target is a directory.
  EXPECT_THROW(write_file_atomically(dir.path() / "missing" / "x.csv", bytes_of("x")), Error);
  fs::create_directory(dir.path() / "sub");
  EXPECT_THROW(write_file_atomically(dir.path() / "sub", bytes_of("x")), Error);
  EXPECT_EQ(names(dir.path()), (std::set<std::string>{"a.png", "a.exr", "run.csv", "run.md", "sub"}));

  // Killed in the middle of the write: the file size limit (SIGXFSZ) stops it at 64 KiB of 1 MiB.
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const rlimit no_core{0, 0}, size{64 << 10, 64 << 10};
    ::setrlimit(RLIMIT_CORE, &no_core);
    ::setrlimit(RLIMIT_FSIZE, &size);
    try {
      write_file_atomically(dir.path() / "big.csv", bytes_of(std::string(1 << 20, 'x')));
    } catch (...) {
    }
    ::_exit(0);  // not reached: SIGXFSZ ends the process
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGXFSZ) << status;
  EXPECT_EQ(names(dir.path()), (std::set<std::string>{"a.png", "a.exr", "run.csv", "run.md", "sub"}));
  // The same for the CLI writing an image.
  r = run_shell("ulimit -c 0; ulimit -f 1; exec " + std::string(SDFBENCH_BINARY) +
                " render --backend embree --scene thesis:sphere:5 --size 256x144 --frames 1 --warmup 0 --out " + d + "big.png");
  EXPECT_EQ(r.exit_code, 128 + SIGXFSZ) << r.output;
  EXPECT_EQ(names(dir.path()), (std::set<std::string>{"a.png", "a.exr", "run.csv", "run.md", "sub"}));
}

// Class 5: a second run writing a --csv that a run is writing is refused, not interleaved.
TEST(OutputSafety, ConcurrentWritersOfOneCsvAreRefused) {
  test::TempDir dir, outside;
  const fs::path csv = dir.path() / "run.csv";
  {
    const OutputLock held(csv, "--csv");  // another run, as far as sdfbench can tell
    expect_user_error(kSweep + " --csv " + csv.string(), "another sdfbench run is writing '" + csv.string() + "'");
    expect_user_error(kSweep + " --csv " + csv.string() + " --resume", "another sdfbench run is writing");
    const fs::path input = outside.write("in.csv", csv_line(measurement_columns()));
    expect_user_error("merge " + input.string() + " --csv " + csv.string(), "another sdfbench run is writing");
    EXPECT_FALSE(fs::exists(csv));
    EXPECT_THROW(OutputLock(csv, "--csv"), Error);  // also within one process
  }
  // Released (and its file removed): the next run goes ahead and leaves only its CSV.
  const test::CommandResult r = sdfbench(kSweep + " --csv " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_csv(csv).rows.size(), 2u);
  EXPECT_EQ(names(dir.path()), std::set<std::string>{"run.csv"});

  // Two real runs at once: while a slow sweep writes the CSV (its lock file is there), another
  // sweep of other configurations is refused, and the first's rows are all in the file.
  const std::string slow = sweep({{"--size", "320x180"}, {"--frames", "30"}, {"--csv", csv.string()}});
  const std::string other = sweep({{"--hash-cell", "20"}, {"--csv", csv.string()}});
  const fs::path lock = dir.path() / ".run.csv.lock";
  const test::CommandResult both =
      run_shell(std::string(SDFBENCH_BINARY) + " " + slow + " >/dev/null 2>&1 & while [ ! -e " + lock.string() +
                " ]; do sleep 0.02; done; " + SDFBENCH_BINARY + " " + other + "; echo second=$?; wait $!; echo first=$?");
  EXPECT_NE(both.output.find("another sdfbench run is writing '" + csv.string() + "'"), std::string::npos) << both.output;
  EXPECT_NE(both.output.find("second=1"), std::string::npos) << both.output;
  EXPECT_NE(both.output.find("first=0"), std::string::npos) << both.output;
  const CsvTable rows = read_csv(csv);
  ASSERT_EQ(rows.rows.size(), 2u);
  for (const auto& row : rows.rows) EXPECT_EQ(row[rows.column("width")], "320");
  EXPECT_EQ(names(dir.path()), std::set<std::string>{"run.csv"});

  // A symlink planted at the lock's name is not followed.
  const fs::path secret = outside.write("secret.txt", "precious");
  fs::create_symlink(secret, dir.path() / ".run.csv.lock");
  expect_user_error(kSweep + " --csv " + csv.string(), "is a symlink");
  EXPECT_EQ(read_file(secret), "precious");
}

// Class 5: --resume refuses a CSV of another run (other settings, a sweep resumed as a table)
// and leaves it as it was; the same flags resume.
TEST(OutputSafety, ResumeRefusesRowsOfAnotherRun) {
  test::TempDir dir;
  const fs::path csv = dir.path() / "run.csv";
  test::CommandResult r = sdfbench(kSweep + " --csv " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string written = read_file(csv);
  const std::pair<std::pair<std::string, std::string>, std::string> cases[] = {
      {{"--max-steps", "100"}, "max_steps '512', this run asks for '100'"},
      {{"--hit-epsilon", "1e-4"}, "hit_epsilon"},
      {{"--hit-footprint", "0.5"}, "hit_footprint"},
      {{"--hit", "thesis"}, "hit 'exact', this run asks for 'thesis'"},
      {{"--cells-per-extent", "9"}, "cells_per_extent '8', this run asks for '9'"},
      {{"--mesh-cell", "0.1"}, "mesh_cell '0', this run asks for '0.1'"},
      {{"--frames", "2"}, "requested_frames '1', this run asks for '2'"},
      {{"--warmup", "1"}, "warmup"},
      {{"--check-size", "16x9"}, "check_size '32x18', this run asks for '16x9'"},
      {{"--budget-s", "10"}, "budget_s"},
      {{"--device", "0"}, "requested_device 'lavapipe', this run asks for '0'"},
      {{"--threads", "7"}, "threads"},
      {{"--size", "16x9"}, "width"},
      {{"--mode", "shadow"}, "mode"},
      // Other structure lists: configuration 1 is depth 1 there, depth 2 here.
      {{"--octree-depth", "0,2"}, "row 2 (run_index 1) was measured with octree_depth '1', this run asks for '2'"},
      {{"--octree-depth", "0"}, "row 2 has run_index 1, but this run has 1 configurations"},
      // The same two configurations at the same places, in a longer list.
      {{"--octree-depth", "0,1,2"}, "row 1 comes from a run of another configuration list (run_id '"},
  };
  for (const auto& [flag, words] : cases)
    expect_user_error(sweep({flag, {"--csv", csv.string()}, {"--resume", ""}}), {words, "belongs to another run"});
  // The sweep's CSV resumed as a table.
  expect_user_error("table --table 6.2 --meshes sphere --objects 4 --backends sdf-cpu --size 32x18 --check-size 32x18 "
                    "--frames 1 --warmup 0 --csv " + csv.string() + " --resume",
                    "was measured with table 'sweep', this run asks for ''");
  EXPECT_EQ(read_file(csv), written);
  r = sdfbench(kSweep + " --csv " + csv.string() + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 configuration(s) already in"), std::string::npos) << r.output;
  EXPECT_EQ(read_csv(csv).rows.size(), 2u);

  // A row repeated or with a bad run_index.
  CsvTable t = read_csv(csv);
  t.rows.push_back(t.rows[0]);
  write_csv(csv, t);
  expect_user_error(kSweep + " --csv " + csv.string() + " --resume", "row 3 measures run_index 0 again");
  t.rows.pop_back();
  t.rows[1][t.column("run_index")] = "x1";
  write_csv(csv, t);
  expect_user_error(kSweep + " --csv " + csv.string() + " --resume", "row 2: run_index 'x1' is not a non-negative integer");
}

// The key that resume and merge share holds every parameter that changes a measurement.
TEST(OutputSafety, ConfigurationKeyCoversEveryMeasurementParameter) {
  const std::vector<std::string>& key = configuration_key_columns();
  for (const char* column : {"lists", "cells_per_extent", "octree_min_size", "max_steps", "hit_epsilon", "hit_footprint",
                             "requested_frames", "warmup", "budget_s", "check_size", "reference", "requested_device",
                             "whitted_passes", "validate", "threads", "hash_cell", "mesh_cell", "hit", "width", "mode"})
    EXPECT_NE(std::find(key.begin(), key.end(), column), key.end()) << column;
  const std::vector<std::string>& columns = measurement_columns();
  for (const std::string& column : key) EXPECT_NE(std::find(columns.begin(), columns.end(), column), columns.end()) << column;
  for (const ParamSpec& spec : param_catalogue())  // every backend's parameter
    EXPECT_NE(std::find(key.begin(), key.end(), spec.name), key.end()) << spec.name;
  Measurement a, b;
  b.backend_params["max_steps"] = "100";
  EXPECT_NE(configuration_key(a), configuration_key(b));
  b = a;
  b.requested_device = "gpu";
  EXPECT_NE(configuration_key(a), configuration_key(b));
  b = a;
  b.fps = 12;  // a result, not a parameter
  EXPECT_EQ(configuration_key(a), configuration_key(b));
}

// Class 4: merge checks the columns it relies on.
TEST(OutputSafety, MergeRefusesABadRunIndexNamingFileRowAndColumn) {
  test::TempDir dir;
  // A file of one row, of scene `name` at `run_index`.
  auto file_with = [&](const std::string& name, const std::string& run_index) {
    Measurement m;
    m.scene = name;
    std::vector<std::string> row = to_csv_fields(m);
    row[0] = run_index;
    return dir.write(name + ".csv", csv_line(measurement_columns()) + csv_line(row));
  };
  const fs::path out = dir.path() / "out.csv";
  for (const char* bad : {"abc", "-1", "", "1.5", "3x", "99999999999999999999999"}) {
    const fs::path in = file_with("bad", bad);
    expect_user_error("merge " + in.string() + " --csv " + out.string(),
                      {in.string() + "' row 1: run_index '" + std::string(bad) + "' is not a non-negative integer"});
  }
  expect_user_error("merge " + dir.write("cols.csv", "run_index,x\n0,1\n").string() + " --csv " + out.string(), "has no column");
  EXPECT_FALSE(fs::exists(out));
  // Valid indices merge, in run_index order.
  const test::CommandResult ok =
      sdfbench("merge " + file_with("b", "7").string() + " " + file_with("a", "3").string() + " --csv " + out.string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("note: 3 configuration(s) below the last run_index are missing (first: run_index 4)"), std::string::npos)
      << ok.output;
  const CsvTable merged = read_csv(out);
  ASSERT_EQ(merged.rows.size(), 2u);
  EXPECT_EQ(merged.rows[0][merged.column("scene")], "a");
  EXPECT_EQ(merged.rows[1][merged.column("run_index")], "7");
  // One place of the run measured twice, as two configurations: not the shards of one run.
  fs::remove(out);
  expect_user_error("merge " + file_with("c", "3").string() + " " + file_with("a", "3").string() + " --csv " + out.string(),
                    "run_index 3 is in the inputs twice, with other configurations");
  EXPECT_FALSE(fs::exists(out));
}

// Class 4: the AOV file must hold all 7 channels.
TEST(OutputSafety, AovFileMustBeExr) {
  test::TempDir dir;
  for (const char* name : {"x.jpg", "x.png", "x.tif"})
    expect_user_error(kRender + " --aov " + (dir.path() / name).string(),
                      {"--aov '" + (dir.path() / name).string() + "'", "only OpenEXR holds (use .exr)"});
  expect_user_error(kRender + " --aov " + (dir.path() / "x").string(), "--aov '" + (dir.path() / "x").string() + "'");
  EXPECT_TRUE(names(dir.path()).empty());
  const test::CommandResult r = sdfbench(kRender + " --aov " + (dir.path() / "x.EXR").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// Class 3 for the CSV readers: a FIFO given to merge or --resume is an error, not a hang.
TEST(OutputSafety, FifoCsvInputsAreErrorsNotHangs) {
  test::TempDir dir;
  const fs::path fifo = dir.path() / "in.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  expect_user_error("merge " + fifo.string() + " --csv " + (dir.path() / "out.csv").string(), "not a regular file");
  expect_user_error(kSweep + " --csv " + fifo.string() + " --resume", "not a regular file");
  expect_user_error("merge /dev/zero --csv " + (dir.path() / "out.csv").string(), "not a regular file");
  EXPECT_THROW(read_csv(fifo), Error);
  EXPECT_EQ(names(dir.path()), std::set<std::string>{"in.csv"});
}

// Issue 27, class 8: one path named twice among the outputs, or an output that is an input,
// is refused at start-up (after resolving `..`, symlinked folders and links), and nothing changes.
TEST(OutputSafety, AnOutputThatIsAnotherOutputOrAnInputIsRefused) {
  const test::TempDir dir;
  const fs::path texture = dir.path() / "wood.png";
  ASSERT_EQ(test::run_sdfbench(kRender + " --out " + texture.string()).exit_code, 0);  // a real PNG to texture with
  const fs::path scene = dir.write("scene.json", R"({"meshes": {"ball": {"builtin": "sphere"}},
      "materials": {"paint": {"albedo": [1, 1, 1], "texture": {"file": "wood.png"}}},
      "instances": [{"mesh": "ball"}], "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]}})");
  fs::create_directory(dir.path() / "sub");
  fs::create_directory_symlink(dir.path(), dir.path() / "alias");
  const std::string render = "render --backend embree --size 16x9 --frames 1 --warmup 0 --scene " + scene.string();
  const std::string sdf_render = "render --backend sdf-cpu --size 16x9 --frames 1 --warmup 0 --scene " + scene.string();
  const std::string x = (dir.path() / "x.exr").string(), x_again = (dir.path() / "sub" / ".." / "x.exr").string();
  const std::string csv = (dir.path() / "x.csv").string();
  const auto before = snapshot(dir.path());
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {render + " --out " + x + " --aov " + x_again, {"--aov", "same file as --out"}},
      {sdf_render + " --out " + x + " --heatmap " + (dir.path() / "alias" / "x.exr").string(), {"--heatmap", "same file"}},
      {render + " --out " + texture.string(), {"--out", "the scene's texture", "destroy an input"}},
      {render + " --out " + (dir.path() / "alias" / "wood.png").string(), {"the scene's texture"}},
      {sdf_render + " --cache " + scene.string(), {"--cache", "--scene"}},
      {"build --scene " + scene.string() + " --cache " + scene.string(), {"--cache", "--scene", "destroy an input"}},
      {kSweep + " --csv " + csv + " --markdown " + csv, {"--markdown", "same file as --csv"}},
      {"table --table 6.3 --meshes sphere --objects 1 --backends embree --csv " + builtin_mesh_path("sphere").string(),
       {"--csv", "the thesis mesh"}},
  };
  for (const auto& [args, words] : cases) expect_user_error(args, words);
  EXPECT_EQ(snapshot(dir.path()), before);
  // compare --out-dir writes DIR/<backend>.png: a texture of that name is an input.
  fs::copy_file(texture, dir.path() / "embree.png");
  const fs::path scene2 = dir.write("scene2.json", R"({"meshes": {"ball": {"builtin": "sphere"}},
      "materials": {"paint": {"albedo": [1, 1, 1], "texture": {"file": "embree.png"}}},
      "instances": [{"mesh": "ball"}], "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]}})");
  expect_user_error("compare --scene " + scene2.string() + " --backends embree,tri-aabb --size 16x9 --out-dir " + dir.path().string(),
                    std::vector<std::string>{"--out-dir image", "embree.png", "the scene's texture"});
  // merge onto one of its inputs.
  const test::CommandResult run = test::run_sdfbench(kSweep + " --csv " + csv);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  expect_user_error("merge " + csv + " --csv " + csv, std::vector<std::string>{"--csv", "the input"});
}

}  // namespace
}  // namespace sdfbench

namespace sdfbench {
namespace {

// A render's SDF cache that cannot be written (a read-only file system: /proc refuses new files,
// even to root) is a warning, and the render goes on; `build`, whose output it is, refuses it.
TEST(OutputSafety, AnUnwritableRenderCacheWarnsAndTheRenderGoesOn) {
  const test::CommandResult r = test::run_sdfbench(
      "render --scene thesis:sphere:1 --backend sdf-octree --size 8x8 --frames 1 --warmup 0 --cache /proc/sdfbench.cache");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("sdfbench: warning: cannot write '/proc/sdfbench.cache'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("FPS"), std::string::npos) << r.output;
  const test::CommandResult build = test::run_sdfbench("build --scene thesis:sphere:1 --cache /proc/sdfbench.cache");
  EXPECT_EQ(build.exit_code, 1) << build.output;
}

}  // namespace
}  // namespace sdfbench

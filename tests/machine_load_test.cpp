// Machine load in every row (issue 30): the load meter against real load, and a table timed
// while other processes spin is flagged in its CSV, its markdown and on stderr.
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "harness/csv.h"
#include "tests/test_support.h"
#include "util/machine_load.h"

namespace sdfbench {
namespace {

// Two shell loops that spin (one per core of the CI machine) for the command, then stop.
std::string with_spinners(const std::string& command) {
  return "spin() { while :; do :; done; }; spin & a=$!; spin & b=$!; sleep 0.3; " + command +
         "; status=$?; kill $a $b; exit $status";
}

TEST(MachineLoad, TheMeterReadsProcAndTheFlagFollowsItsLimits) {
  LoadMeter meter;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::optional<MachineLoad> load = meter.stop();
  ASSERT_TRUE(load.has_value());  // Linux: /proc is there
  EXPECT_GE(load->load_avg, 0.0);
  EXPECT_GE(load->steal_pct, 0.0);
  EXPECT_GE(load->other_pct, 0.0);
  EXPECT_LE(load->other_pct + load->steal_pct, 100.0 + 1e-9);
  MachineLoad busy;
  busy.window_cpu_s = kMinJudgedCpuSeconds;
  busy.other_pct = kBusyOtherPct + 1.0;
  EXPECT_TRUE(busy.busy(2));
  busy.window_cpu_s = kMinJudgedCpuSeconds / 2;  // a few clock ticks: the shares are noise
  EXPECT_FALSE(busy.busy(2));
  busy = MachineLoad{};
  busy.window_cpu_s = kMinJudgedCpuSeconds;
  busy.steal_pct = kBusyStealPct + 1.0;
  EXPECT_TRUE(busy.busy(2));
  busy = MachineLoad{};
  busy.load_avg = 3.5;
  EXPECT_TRUE(busy.busy(2));
  EXPECT_FALSE(busy.busy(4));
  EXPECT_FALSE(MachineLoad{}.busy(2));
}

// A table timed while two other processes spin (1000 frames or 2 s per row: a window long enough
// for the CPU shares to be judged, kMinJudgedCpuSeconds): every row's load columns are filled, its rows
// are flagged busy (the spinners take most of the CPUs), the markdown marks them and stderr says
// so once.
TEST(MachineLoad, ATableTimedOnABusyMachineIsFlagged) {
  test::TempDir dir;
  const auto csv = dir.path() / "busy.csv", md = dir.path() / "busy.md";
  const std::string table = std::string(SDFBENCH_BINARY) +
                            " table --table 6.3 --mode primary --meshes sphere --objects 1 --backends embree,bvh "
                            "--size 320x180 --check-size 32x18 --frames 1000 --warmup 1 --budget-s 2 --csv " +
                            csv.string() + " --markdown " + md.string();
  const test::CommandResult r = test::run_shell(with_spinners(table), 120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable rows = read_csv(csv);
  ASSERT_EQ(rows.rows.size(), 2u);
  for (const auto& row : rows.rows) {
    for (const char* column : {"load_avg", "cpu_steal_pct", "cpu_other_pct", "busy"})
      EXPECT_FALSE(row[rows.column(column)].empty()) << column;
    EXPECT_EQ(row[rows.column("busy")], "1") << "other processes " << row[rows.column("cpu_other_pct")] << " %";
  }
  size_t warnings = 0;
  for (size_t at = r.output.find("machine was busy"); at != std::string::npos; at = r.output.find("machine was busy", at + 1))
    ++warnings;
  EXPECT_EQ(warnings, 1u) << r.output;
  const test::CommandResult markdown = test::run_command("cat " + md.string());
  EXPECT_NE(markdown.output.find("‡"), std::string::npos) << markdown.output;
}

}  // namespace
}  // namespace sdfbench

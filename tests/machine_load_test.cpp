// Machine load in every row (issue 30): the load meter against real load, and a table timed
// while other processes spin is flagged in its CSV, its markdown and on stderr.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "harness/csv.h"
#include "tests/test_support.h"
#include "util/machine_load.h"

namespace sdfbench {
namespace {

// A spinning shell loop per CPU of the machine (whatever its core count) for the command, then stop.
std::string with_spinners(const std::string& command) {
  return "spin() { while :; do :; done; }; pids=; for i in $(seq $((2 * $(nproc)))); do spin & pids=\"$pids $!\"; done; sleep 0.3; " +
         command + "; status=$?; kill $pids; exit $status";
}

// A /proc of known tick counts: stat's first line, self/stat's utime and stime, loadavg.
void write_proc(const std::filesystem::path& root, const std::string& cpu, uint64_t utime, uint64_t stime, double loadavg) {
  std::filesystem::create_directories(root / "self");
  std::ofstream(root / "stat") << "cpu " << cpu << "\ncpu0 1 2 3\n";
  std::ofstream(root / "self" / "stat") << "4242 (sdf bench) R 1 2 3 4 5 6 7 8 9 10 " << utime << " " << stime << " 0 0\n";
  std::ofstream(root / "loadavg") << loadavg << " 0.5 0.5 1/100 4242\n";
}

// The meter's shares from known tick deltas (1000 ticks over all CPUs): an idle machine, one
// where other processes used 20 %, one where the hypervisor stole 10 %.
TEST(MachineLoad, TheMeterTurnsTickDeltasIntoShares) {
  const test::TempDir dir;
  const auto measure = [&](const std::string& end_cpu, uint64_t end_utime, double loadavg) {
    write_proc(dir.path(), "100 0 100 800 0 0 0 0", 50, 50, 0.1);  // total 1000, busy 200, this process 100
    const LoadMeter meter(dir.path());
    write_proc(dir.path(), end_cpu, end_utime, 50, loadavg);
    const std::optional<MachineLoad> load = meter.stop();
    EXPECT_TRUE(load.has_value());
    return load.value_or(MachineLoad{});
  };
  const MachineLoad idle = measure("200 0 100 1700 0 0 0 0", 150, 0.1);  // busy + 100 ticks, all this process'
  EXPECT_DOUBLE_EQ(idle.other_pct, 0.0);
  EXPECT_DOUBLE_EQ(idle.steal_pct, 0.0);
  EXPECT_DOUBLE_EQ(idle.window_cpu_s, 1000.0 / static_cast<double>(sysconf(_SC_CLK_TCK)));
  EXPECT_FALSE(idle.busy(2));
  const MachineLoad others = measure("400 0 100 1500 0 0 0 0", 150, 0.1);  // busy + 300, this process 100
  EXPECT_DOUBLE_EQ(others.other_pct, 20.0);
  EXPECT_TRUE(others.busy(2));
  const MachineLoad stolen = measure("200 0 100 1600 0 0 0 100", 150, 0.1);  // steal + 100
  EXPECT_DOUBLE_EQ(stolen.steal_pct, 10.0);
  EXPECT_DOUBLE_EQ(stolen.other_pct, 0.0);
  EXPECT_TRUE(stolen.busy(2));
  EXPECT_DOUBLE_EQ(measure("200 0 100 1700 0 0 0 0", 150, 3.5).load_avg, 3.5);
  std::filesystem::remove(dir.path() / "loadavg");
  EXPECT_FALSE(LoadMeter(dir.path()).stop().has_value()) << "an unreadable /proc gives no load";
}

TEST(MachineLoad, TheMeterReadsProcAndTheFlagFollowsItsLimits) {
  LoadMeter meter;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_TRUE(meter.stop().has_value());  // Linux: /proc is there
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

// A table timed while two other processes per CPU spin (one per CPU once left a row unflagged in a
// CI run, the message now gives every load column), 1000 frames or 4 s per row (the warm-up frame, a kernel compile under the spinners, counts in it): a window long
// enough for the CPU shares to be judged (kMinJudgedCpuSeconds): every row's load columns are filled, its rows
// are flagged busy (the spinners take most of the CPUs), the markdown marks them and stderr says
// so once.
TEST(MachineLoad, ATableTimedOnABusyMachineIsFlagged) {
  test::TempDir dir;
  const auto csv = dir.path() / "busy.csv", md = dir.path() / "busy.md";
  const std::string table = std::string(SDFBENCH_BINARY) +
                            " table --table 6.3 --mode primary --meshes sphere --objects 1 --backends embree,bvh "
                            "--size 320x180 --check-size 32x18 --frames 1000 --warmup 1 --budget-s 4 --csv " +
                            csv.string() + " --markdown " + md.string();
  const test::CommandResult r = test::run_shell(with_spinners(table), 120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable rows = read_csv(csv);
  ASSERT_EQ(rows.rows.size(), 2u);
  for (const auto& row : rows.rows) {
    for (const char* column : {"load_avg", "cpu_steal_pct", "cpu_other_pct", "busy"})
      EXPECT_FALSE(row[rows.column(column)].empty()) << column;
    EXPECT_EQ(row[rows.column("busy")], "1") << "other processes " << row[rows.column("cpu_other_pct")] << " %, steal "
                                             << row[rows.column("cpu_steal_pct")] << " %, load average "
                                             << row[rows.column("load_avg")];
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

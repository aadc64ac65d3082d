#pragma once
// How busy the machine was while a row was timed (issue 30): sdfbench runs on shared VMs whose
// other tenants and processes show up in timings, so every row records, from /proc, the 1-minute
// load average and, over its timed frames, the share of CPU time the hypervisor stole and the share
// other processes used. A row timed on a busy machine is flagged (MachineLoad::busy).
#include <cstdint>
#include <filesystem>
#include <optional>

namespace sdfbench {

struct MachineLoad {
  double load_avg = 0.0;   // /proc/loadavg, 1 minute, at the interval's end
  double steal_pct = 0.0;  // CPU time stolen by the hypervisor, % of all CPUs' time over the interval
  double other_pct = 0.0;  // CPU time used by other processes, % of all CPUs' time over the interval
  double window_cpu_s = 0.0;  // the interval's length summed over all CPUs (what the shares divide by)
  // Busy: a load average above 1.5x the core count (this process alone accounts for up to one
  // runnable thread per core), or, over a window of at least kMinJudgedCpuSeconds, steal above
  // kBusyStealPct or other processes above kBusyOtherPct. /proc counts in clock ticks (10 ms), so
  // in a shorter window one tick of a daemon is already tens of percent: not a busy machine.
  bool busy(unsigned cores) const;
};
inline constexpr double kBusyStealPct = 5.0;
inline constexpr double kBusyOtherPct = 10.0;
inline constexpr double kMinJudgedCpuSeconds = 0.5;

// Starts measuring when made; stop() gives the interval's load, or nothing where /proc cannot be
// read (not Linux, a sandbox): the row's load columns stay empty then. `proc`: where stat,
// self/stat and loadavg are read (tests give known tick counts).
class LoadMeter {
 public:
  explicit LoadMeter(std::filesystem::path proc = "/proc");
  std::optional<MachineLoad> stop() const;

 private:
  struct Ticks {
    uint64_t total = 0, busy = 0, steal = 0, self = 0;
  };
  std::optional<Ticks> read_ticks() const;
  std::filesystem::path proc_;
  std::optional<Ticks> start_;
};

}  // namespace sdfbench

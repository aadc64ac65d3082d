#include "util/machine_load.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <utility>

namespace sdfbench {

bool MachineLoad::busy(unsigned cores) const {
  const bool judged = window_cpu_s >= kMinJudgedCpuSeconds;
  return (judged && (steal_pct > kBusyStealPct || other_pct > kBusyOtherPct)) || load_avg > 1.5 * static_cast<double>(cores);
}

LoadMeter::LoadMeter(std::filesystem::path proc) : proc_(std::move(proc)), start_(read_ticks()) {}

std::optional<LoadMeter::Ticks> LoadMeter::read_ticks() const {
  // /proc/stat's first line: cpu user nice system idle iowait irq softirq steal guest guest_nice
  // (clock ticks over all CPUs; guest time is already inside user).
  std::ifstream stat(proc_ / "stat");
  std::string cpu;
  uint64_t v[8] = {};
  if (!(stat >> cpu >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> v[7]) || cpu != "cpu") return std::nullopt;
  Ticks t;
  for (uint64_t x : v) t.total += x;
  t.busy = v[0] + v[1] + v[2] + v[5] + v[6];
  t.steal = v[7];
  // /proc/self/stat: utime and stime (fields 14 and 15, every thread), after the command name,
  // which may hold spaces: counted from its closing parenthesis.
  std::ifstream self(proc_ / "self" / "stat");
  std::string line;
  if (!std::getline(self, line)) return std::nullopt;
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream fields(line.substr(close + 2));
  std::string field;
  uint64_t utime = 0, stime = 0;
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  t.self = utime + stime;
  return t;
}

std::optional<MachineLoad> LoadMeter::stop() const {
  const std::optional<Ticks> end = read_ticks();
  std::ifstream loadavg(proc_ / "loadavg");
  MachineLoad load;
  if (!start_ || !end || !(loadavg >> load.load_avg)) return std::nullopt;
  const double total = static_cast<double>(end->total - start_->total);
  if (total > 0.0) {
    load.window_cpu_s = total / static_cast<double>(sysconf(_SC_CLK_TCK));
    load.steal_pct = 100.0 * static_cast<double>(end->steal - start_->steal) / total;
    const double busy = static_cast<double>(end->busy - start_->busy), self = static_cast<double>(end->self - start_->self);
    load.other_pct = busy > self ? 100.0 * (busy - self) / total : 0.0;
  }
  return load;
}

}  // namespace sdfbench

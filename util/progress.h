#pragma once
// Progress of a long build (a mesh grid of millions of triangles, a deep octree): once it has
// run for a few seconds, a line on stderr every few seconds, so that a slow build is never
// silent. Header-only; advance() may be called from any thread (TBB workers).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

namespace sdfbench {

class ProgressMeter {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kFirstLine{3}, kInterval{5};

  // `what` names the build ("mesh grid 'bunny'"), `total` its units of work ("rows of cells").
  ProgressMeter(std::string what, uint64_t total, std::string unit)
      : what_(std::move(what)), unit_(std::move(unit)), total_(total), start_(Clock::now()), next_(start_ + kFirstLine) {}

  // n more units done; `detail` (optional) adds to the line, e.g. the memory used so far.
  // advance(0, detail) reports on a unit that is taking long.
  void advance(uint64_t n, const std::function<std::string()>& detail = {}) {
    const uint64_t done = done_.fetch_add(n, std::memory_order_relaxed) + n;
    const Clock::time_point now = Clock::now();
    if (now < next_.load(std::memory_order_relaxed)) return;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock() || now < next_.load(std::memory_order_relaxed)) return;
    next_.store(now + kInterval, std::memory_order_relaxed);
    const double seconds = std::chrono::duration<double>(now - start_).count();
    const std::string extra = detail ? ", " + detail() : std::string();
    const double fraction = total_ ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
    char left[48] = "";
    if (fraction > 0.0 && fraction < 1.0) std::snprintf(left, sizeof left, " (about %.0f s left)", seconds * (1.0 - fraction) / fraction);
    std::fprintf(stderr, "  %s: %llu of %llu %s (%.0f %%), %.0f s%s%s\n", what_.c_str(),
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_), unit_.c_str(),
                 100.0 * fraction, seconds, left, extra.c_str());
    std::fflush(stderr);
  }

 private:
  std::string what_, unit_;
  uint64_t total_;
  Clock::time_point start_;
  std::atomic<uint64_t> done_{0};
  std::atomic<Clock::time_point> next_;
  std::mutex mutex_;
};

}  // namespace sdfbench

// Wall-clock seconds since a steady-clock time point: the per-stage timings of every command's report.
#pragma once

#include <chrono>

namespace lc2wf {

using SteadyClock = std::chrono::steady_clock;

inline double seconds_since(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

}  // namespace lc2wf

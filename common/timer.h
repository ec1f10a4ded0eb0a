// common/timer.h — wall-clock timing for profiles and stats: one steady clock and one way to
// turn two of its instants into milliseconds, for every module's pass timings.
#pragma once

#include <chrono>

namespace softmol {

using Clock = std::chrono::steady_clock;

inline double MsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

inline double MsSince(Clock::time_point a) { return MsBetween(a, Clock::now()); }

}  // namespace softmol

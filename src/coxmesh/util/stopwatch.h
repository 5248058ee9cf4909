// Phase timings for reports: wall-clock seconds since a time point.
#pragma once

#include <chrono>

namespace coxmesh {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace coxmesh

#pragma once

// Small formatting shared by the benchmark drivers' reports.

#include <string>

namespace fleetmap::bench {

// `value` with exactly `digits` decimals ("3.14").
std::string Fixed(double value, int digits);

// The machine a benchmark ran on, for its report: CPU model and hardware threads, e.g.
// "AMD EPYC 7B13, 2 hardware threads (shared), one thread used".
std::string MachineDescription();

}  // namespace fleetmap::bench

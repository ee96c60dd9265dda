#pragma once

// Small formatting shared by the benchmark drivers' reports.

#include <cstddef>
#include <string>
#include <vector>

namespace fleetmap::bench {

// `value` with exactly `digits` decimals ("3.14").
std::string Fixed(double value, int digits);

// `value` through a printf format of one double ("%.1f %%", "%g").
std::string FormatDouble(const char* format, double value);

// The median of `values` (the mean of the middle two for an even count; 0 for none).
double Median(std::vector<double> values);

// Bytes as KB (1024 bytes) with one decimal, as the byte tables print them.
std::string Kilobytes(size_t bytes);

// The machine a benchmark ran on, for its report: CPU model and hardware threads, e.g.
// "AMD EPYC 7B13, 2 hardware threads (shared), one thread used".
std::string MachineDescription();

}  // namespace fleetmap::bench

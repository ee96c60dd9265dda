#pragma once

// Numbers as people and files should see them: without the float noise of binary arithmetic
// (42.175000000000004) or of a float32 widened to double (0.05000000074505806), with the digits
// they have (docs/file-formats.md, "Numbers").

#include <string>

namespace fleetmap {

// The shortest readable form of a number for messages: 0.05, not 0.050000 (printf's %g).
std::string ShortNumber(double value);

// The shortest decimal that reads back as the same double: "0.05", "-38.4", "1e-12".
std::string ExactNumber(double value);

// The number a file should carry: when a decimal of at most 9 places lies within 1e-12 of `value`
// (relative to |value| above 1), that decimal in shortest form, else ExactNumber. Binary
// arithmetic's noise goes (-38.400000000000006 is "-38.4", 1.2e-17 is "0"), any digit a person or
// a sensor gave stays. The value read back is within 1e-12 of `value`, and equal to it when it was
// read from such a decimal.
std::string CleanNumber(double value);

// At most `decimals` digits after the point, trailing zeros dropped: 50.00000089 at 3 is "50",
// 0.560381 at 3 is "0.56", 194.006 at 1 is "194"; a value that rounds to zero is "0", never "-0".
// `decimals` in [0, 15].
std::string FixedNumber(double value, int decimals);

// `value` rounded to `decimals` digits after the point, as the double nearest that decimal, so
// that a shortest-form writer (JSON, ExactNumber) prints the decimal: 42.175000000000004 at 6 is
// 42.175. `decimals` in [0, 15]; non-finite values and values too large to carry that many
// decimals come back unchanged.
double RoundToDecimals(double value, int decimals);

// The double nearest the shortest decimal that reads back as `value`: 0.05F gives 0.05, where
// static_cast<double> gives 0.05000000074505806. For float32 fields of messages and files that
// carry a decimal a person wrote (a map_server resolution), so that it compares, prints and is
// written again as that decimal. Non-finite values come back as they are.
double DoubleFromFloat(float value);

}  // namespace fleetmap

#include "common/core/number_format.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "common/core/check.hpp"

namespace fleetmap {
namespace {

// 10^decimals, exact as a double for decimals <= 22.
double PowerOfTen(int decimals) {
  double scale = 1.0;
  for (int i = 0; i < decimals; ++i) scale *= 10.0;
  return scale;
}

}  // namespace

std::string ShortNumber(double value) {
  std::array<char, 32> buffer;
  std::snprintf(buffer.data(), buffer.size(), "%g", value);
  return buffer.data();
}

std::string ExactNumber(double value) {
  std::array<char, 64> buffer;
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

std::string CleanNumber(double value) {
  constexpr int kDecimals = 9;
  if (!std::isfinite(value)) return ExactNumber(value);
  const double decimal = RoundToDecimals(value, kDecimals);
  const double noise = 1e-12 * std::max(1.0, std::abs(value));
  return ExactNumber(std::abs(decimal - value) <= noise ? decimal : value);
}

std::string FixedNumber(double value, int decimals) {
  FLEETMAP_CHECK(decimals >= 0 && decimals <= 15, "decimals must be in [0, 15]");
  if (!std::isfinite(value)) return ExactNumber(value);
  std::array<char, 400> buffer;  // %f of the largest double has 309 digits before the point
  std::snprintf(buffer.data(), buffer.size(), "%.*f", decimals, value);
  std::string text = buffer.data();
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

double RoundToDecimals(double value, int decimals) {
  FLEETMAP_CHECK(decimals >= 0 && decimals <= 15, "decimals must be in [0, 15]");
  const double scale = PowerOfTen(decimals);
  const double scaled = value * scale;
  // Past 2^52 a double has no fraction left to round (and the product may overflow).
  if (!std::isfinite(scaled) || std::abs(scaled) >= 4503599627370496.0) return value;
  // The quotient of two exact doubles is correctly rounded: the double nearest the decimal.
  const double rounded = std::round(scaled) / scale;
  return rounded == 0.0 ? 0.0 : rounded;
}

double DoubleFromFloat(float value) {
  if (!std::isfinite(value)) return value;
  std::array<char, 64> buffer;
  const auto written = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  double out = value;
  std::from_chars(buffer.data(), written.ptr, out);
  return out;
}

}  // namespace fleetmap

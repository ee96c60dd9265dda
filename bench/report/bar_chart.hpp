#pragma once

// Grouped bar charts as PNG files, drawn with OpenCV imgproc (no plotting library): one group of
// bars per label, one colour per series, a legend, value labels, linear or log10 axis.

#include <optional>
#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::bench {

struct BarChart {
  std::string title;
  std::string y_label;
  std::vector<std::string> groups;  // x axis
  std::vector<std::string> series;  // legend
  // values[group][series]; an empty optional draws no bar ("undefined").
  std::vector<std::vector<std::optional<double>>> values;
  bool log_scale = false;       // log10 axis (values must be > 0)
  std::optional<double> y_max;  // linear axis top; default: the largest value
};

// Errors: kInvalidArgument when values are not shaped groups x series; kUnavailable when the file
// cannot be written (grid::WriteImageFile).
Status WriteBarChartPng(const BarChart& chart, const std::string& path);

}  // namespace fleetmap::bench

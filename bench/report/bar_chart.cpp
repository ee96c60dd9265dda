#include "bench/report/bar_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "common/grid/image_file.hpp"

namespace fleetmap::bench {
namespace {

const cv::Scalar kPalette[] = {{180, 119, 31},  {44, 160, 44},  {40, 100, 180},
                               {189, 103, 148}, {14, 127, 255}, {75, 86, 140}};

std::string Label(double value) {
  char buffer[32];
  if (std::abs(value) >= 100.0) {
    std::snprintf(buffer, sizeof(buffer), "%.0f", value);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%.1f", value);
  }
  return buffer;
}

}  // namespace

Status WriteBarChartPng(const BarChart& chart, const std::string& path) {
  if (chart.values.size() != chart.groups.size()) {
    return InvalidArgumentError("bar chart " + chart.title + ": one row of values per group");
  }
  for (const auto& row : chart.values) {
    if (row.size() != chart.series.size()) {
      return InvalidArgumentError("bar chart " + chart.title + ": one value per series");
    }
  }
  const int group_width = std::max(120, 34 * static_cast<int>(chart.series.size()) + 30);
  const int left = 80, right = 30, top = 60, bottom = 70;
  const int plot_h = 360;
  const int width = left + right + group_width * static_cast<int>(chart.groups.size());
  const int height = top + plot_h + bottom;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto font = cv::FONT_HERSHEY_SIMPLEX;

  double max_value = 0.0, min_positive = 0.0;
  for (const auto& row : chart.values) {
    for (const auto& v : row) {
      if (!v) continue;
      max_value = std::max(max_value, *v);
      if (*v > 0.0) min_positive = min_positive == 0.0 ? *v : std::min(min_positive, *v);
    }
  }
  double lo = 0.0, hi = chart.y_max.value_or(max_value > 0.0 ? max_value * 1.1 : 1.0);
  if (chart.log_scale) {
    lo = std::floor(std::log10(min_positive > 0.0 ? min_positive : 1.0));
    hi = std::ceil(std::log10(max_value > 0.0 ? max_value : 10.0) + 0.01);
    if (hi <= lo) hi = lo + 1.0;
  }
  auto y_of = [&](double v) {
    const double t =
        chart.log_scale ? (std::log10(std::max(v, 1e-12)) - lo) / (hi - lo) : (v - lo) / (hi - lo);
    return top + plot_h - static_cast<int>(std::lround(std::clamp(t, 0.0, 1.0) * plot_h));
  };
  // Axis, grid lines and tick labels.
  const int ticks = chart.log_scale ? static_cast<int>(hi - lo) : 5;
  for (int i = 0; i <= ticks; ++i) {
    const double v = chart.log_scale ? std::pow(10.0, lo + i) : lo + (hi - lo) * i / ticks;
    const int y = y_of(v);
    cv::line(image, {left, y}, {width - right, y}, cv::Scalar(225, 225, 225), 1);
    cv::putText(image, Label(v), {5, y + 5}, font, 0.45, cv::Scalar(60, 60, 60), 1, cv::LINE_AA);
  }
  cv::line(image, {left, top}, {left, top + plot_h}, cv::Scalar(0, 0, 0), 1);
  cv::line(image, {left, top + plot_h}, {width - right, top + plot_h}, cv::Scalar(0, 0, 0), 1);
  cv::putText(image, chart.title, {left, 24}, font, 0.6, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(image, chart.y_label, {5, 46}, font, 0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  // Legend.
  int legend_x = left;
  for (size_t s = 0; s < chart.series.size(); ++s) {
    const int y = height - 22;
    cv::rectangle(image, {legend_x, y - 10}, {legend_x + 12, y + 2}, kPalette[s % 6], cv::FILLED);
    cv::putText(image, chart.series[s], {legend_x + 16, y}, font, 0.45, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
    legend_x += 30 + 8 * static_cast<int>(chart.series[s].size());
  }
  // Bars.
  const int bar_w = (group_width - 30) / std::max<int>(1, static_cast<int>(chart.series.size()));
  for (size_t g = 0; g < chart.groups.size(); ++g) {
    const int x0 = left + static_cast<int>(g) * group_width + 15;
    for (size_t s = 0; s < chart.series.size(); ++s) {
      const std::optional<double>& v = chart.values[g][s];
      const int x = x0 + static_cast<int>(s) * bar_w;
      if (!v) {
        cv::putText(image, "n/a", {x + 2, top + plot_h - 4}, font, 0.35, cv::Scalar(0, 0, 200), 1,
                    cv::LINE_AA);
        continue;
      }
      const int y = y_of(*v);
      cv::rectangle(image, {x + 2, y}, {x + bar_w - 2, top + plot_h}, kPalette[s % 6], cv::FILLED);
      cv::putText(image, Label(*v), {x + 1, std::max(top - 4, y - 4)}, font, 0.33,
                  cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
    cv::putText(image, chart.groups[g], {x0, top + plot_h + 20}, font, 0.5, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
  }
  return grid::WriteImageFile(path, image);
}

}  // namespace fleetmap::bench

#include "cli/learn_progress_printer.hpp"

namespace fleetmap::cli {

LearnProgressPrinter::LearnProgressPrinter(std::ostream& out, bool terminal,
                                           std::chrono::milliseconds terminal_interval,
                                           std::chrono::milliseconds log_interval)
    : out_(out),
      terminal_(terminal),
      terminal_interval_(terminal_interval),
      log_interval_(log_interval) {}

void LearnProgressPrinter::Report(const object_learning::LearnProgress& progress) {
  const auto now = std::chrono::steady_clock::now();
  const bool stage_changed = !printed_ || progress.stage != last_stage_;
  const auto interval = terminal_ ? terminal_interval_ : log_interval_;
  if (!stage_changed && now - last_ < interval) return;
  const std::string line = "learn-objects: " + object_learning::DescribeProgress(progress);
  if (terminal_) {
    out_ << "\r" << line;
    if (line.size() < last_width_) out_ << std::string(last_width_ - line.size(), ' ');
    last_width_ = line.size();
    if (progress.stage == object_learning::LearnStage::kDone) out_ << "\n";
  } else {
    out_ << line << "\n";
  }
  out_.flush();
  last_ = now;
  printed_ = true;
  last_stage_ = progress.stage;
}

}  // namespace fleetmap::cli

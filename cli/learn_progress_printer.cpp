#include "cli/learn_progress_printer.hpp"

#include <string>

namespace fleetmap::cli {

LearnProgressPrinter::LearnProgressPrinter(std::ostream& out, bool terminal,
                                           std::chrono::milliseconds terminal_interval,
                                           std::chrono::milliseconds log_interval)
    : line_(out, {.terminal = terminal,
                  .log_period = log_interval,
                  .terminal_period = terminal_interval}) {}

void LearnProgressPrinter::Report(const object_learning::LearnProgress& progress) {
  const std::string text = "learn-objects: " + object_learning::DescribeProgress(progress);
  if (progress.stage == object_learning::LearnStage::kDone) {
    line_.Finish(text);
  } else if (!reported_ || progress.stage != last_stage_) {
    line_.Milestone(text);
  } else {
    line_.Update(text);
  }
  reported_ = true;
  last_stage_ = progress.stage;
}

}  // namespace fleetmap::cli

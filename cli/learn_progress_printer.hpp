#pragma once

// Draws object learning's progress (LearnProgress) on a stream for `fleetmap learn-objects`, on
// one ProgressLine: on a terminal, one line redrawn in place at most every `terminal_interval`;
// otherwise (a log file, a pipe) a new line at most every `log_interval`, and on every stage
// change, so a slow run is told from a hung one either way. Stage changes always print; the last
// report ends the line.
//
// Thread-safety: call from one thread (the learner's progress callback runs on its thread).

#include <chrono>
#include <ostream>

#include "common/core/progress_line.hpp"
#include "common/object_learning/learn_progress.hpp"

namespace fleetmap::cli {

class LearnProgressPrinter {
 public:
  LearnProgressPrinter(std::ostream& out, bool terminal,
                       std::chrono::milliseconds terminal_interval = std::chrono::milliseconds(200),
                       std::chrono::milliseconds log_interval = std::chrono::seconds(10));

  void Report(const object_learning::LearnProgress& progress);

 private:
  ProgressLine line_;
  bool reported_ = false;
  object_learning::LearnStage last_stage_ = object_learning::LearnStage::kExtracting;
};

}  // namespace fleetmap::cli

#pragma once

// What object learning is doing, for a progress display: the learner reports through
// LearnOptions::progress and never prints (the CLI draws a line on stderr, the server logs at a
// low rate and counts).

#include <functional>
#include <string>

namespace fleetmap::object_learning {

// In the order a run goes through them; a report's stage never goes back.
enum class LearnStage : int {
  kExtracting = 0,  // differencing the maps into snapshots
  kSearching = 1,   // EM for the candidate (N, M)s
  kDone = 2,
};

const char* LearnStageName(LearnStage stage);

struct LearnProgress {
  LearnStage stage = LearnStage::kExtracting;
  int maps = 0;
  int snapshots = 0;  // 0 while extracting
  // The candidate now running (0 before the search), and the search so far.
  int num_objects = 0;
  int num_templates = 0;
  int candidates_done = 0;      // (N, M) runs finished, restarts included as one
  int candidates_estimate = 0;  // done plus an estimate of those left (patience-based)
  int restart = 0;              // 0-based, of `restarts`
  int restarts = 0;
  int em_iteration = 0;  // iterations done in the current EM run, of at most em_iterations
  int em_iterations = 0;
  double elapsed_seconds = 0.0;
  double remaining_seconds = -1.0;  // estimate; negative: not known yet
};

// One line for people: "searching (N 40, M 3): candidate 5 of ~9, EM iteration 12/30, 14.2 s,
// ~20 s left".
std::string DescribeProgress(const LearnProgress& progress);

// Called on the learning thread, from stage changes up to once per EM iteration: it must be cheap
// and must not throw. Empty: no reports.
using LearnProgressCallback = std::function<void(const LearnProgress&)>;

}  // namespace fleetmap::object_learning

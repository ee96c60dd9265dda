#include "common/object_learning/learn_progress.hpp"

#include <cmath>
#include <cstdio>

namespace fleetmap::object_learning {
namespace {

std::string Seconds(double seconds) {
  char text[32];
  if (seconds < 100.0) {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  } else {
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  }
  return text;
}

}  // namespace

const char* LearnStageName(LearnStage stage) {
  switch (stage) {
    case LearnStage::kExtracting:
      return "extracting";
    case LearnStage::kSearching:
      return "searching";
    case LearnStage::kDone:
      return "done";
  }
  return "?";
}

std::string DescribeProgress(const LearnProgress& p) {
  std::string line = LearnStageName(p.stage);
  switch (p.stage) {
    case LearnStage::kExtracting:
      line += " snapshots from " + std::to_string(p.maps) + " maps";
      break;
    case LearnStage::kSearching:
      line += " (N " + std::to_string(p.num_objects) + ", M " + std::to_string(p.num_templates) +
              "): candidate " + std::to_string(p.candidates_done + 1) + " of ~" +
              std::to_string(p.candidates_estimate) + ", " + std::to_string(p.snapshots) +
              " snapshots";
      if (p.restarts > 1) {
        line += ", start " + std::to_string(p.restart + 1) + "/" + std::to_string(p.restarts);
      }
      line += ", EM iteration " + std::to_string(p.em_iteration) + "/" +
              std::to_string(p.em_iterations);
      break;
    case LearnStage::kDone:
      line += ": " + std::to_string(p.num_objects) + " objects, " +
              std::to_string(p.num_templates) + " templates, " + std::to_string(p.candidates_done) +
              " (N, M) searched";
      break;
  }
  line += ", " + Seconds(p.elapsed_seconds);
  if (p.stage != LearnStage::kDone && p.remaining_seconds >= 0.0) {
    line += ", ~" + Seconds(p.remaining_seconds) + " left";
  }
  return line;
}

}  // namespace fleetmap::object_learning

#include "bench/objects/real_plan_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <set>
#include <string>
#include <tuple>

namespace fleetmap::bench {
namespace {

// Resets the kernel's peak-RSS mark of this process (Linux: "5" to clear_refs), so that VmHWM
// afterwards is the peak of what follows. False where that is not allowed.
bool ResetPeakMemory() {
  std::ofstream clear_refs("/proc/self/clear_refs");
  if (!clear_refs) return false;
  clear_refs << "5";
  clear_refs.flush();
  return static_cast<bool>(clear_refs);
}

// This process's peak resident memory since the last reset (VmHWM of /proc/self/status), or -1.
int64_t PeakMemoryBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6)) * 1024;
  }
  return -1;
}

}  // namespace

RealPlanScore ScoreAgainstPieces(const RealPlanSeries& series,
                                 const object_learning::LearnedModel& model,
                                 double match_distance) {
  RealPlanScore score;
  score.snapshots = static_cast<int>(model.snapshots.size());
  for (size_t t = 0; t < series.pieces.size(); ++t) {
    const std::vector<PlacedPiece>& pieces = series.pieces[t];
    score.true_pieces += static_cast<int>(pieces.size());
    std::vector<std::tuple<double, int, int>> pairs;  // distance, snapshot, piece
    for (size_t s = 0; s < model.snapshots.size(); ++s) {
      if (model.snapshots[s].map_index != static_cast<int>(t)) continue;
      for (size_t p = 0; p < pieces.size(); ++p) {
        const double d = (model.snapshots[s].centre - pieces[p].centre).norm();
        if (d <= match_distance) pairs.emplace_back(d, static_cast<int>(s), static_cast<int>(p));
      }
    }
    std::sort(pairs.begin(), pairs.end());
    std::set<int> used_snapshots, used_pieces;
    for (const auto& [d, s, p] : pairs) {
      if (used_snapshots.count(s) || used_pieces.count(p)) continue;
      used_snapshots.insert(s);
      used_pieces.insert(p);
      ++score.matched;
    }
    for (size_t p = 0; p < pieces.size(); ++p) {
      if (used_pieces.count(static_cast<int>(p))) continue;
      score.missed.push_back(pieces[p]);
      score.missed_map.push_back(static_cast<int>(t));
    }
    for (size_t s = 0; s < model.snapshots.size(); ++s) {
      if (model.snapshots[s].map_index == static_cast<int>(t) &&
          !used_snapshots.count(static_cast<int>(s))) {
        score.spurious.push_back(model.snapshots[s]);
      }
    }
  }
  score.precision =
      score.snapshots == 0 ? 0.0 : static_cast<double>(score.matched) / score.snapshots;
  score.recall =
      score.true_pieces == 0 ? 0.0 : static_cast<double>(score.matched) / score.true_pieces;
  return score;
}

StatusOr<RealPlanResult> RunRealPlanExperiment(const RealPlanSeries& series,
                                               const object_learning::LearnOptions& learn,
                                               double match_distance) {
  RealPlanResult result;
  result.floor = series.floor;
  result.maps = static_cast<int>(series.maps.size());
  result.unplaced = series.unplaced;
  std::set<int> shapes;
  for (const std::vector<PlacedPiece>& map : series.pieces) {
    result.pieces = std::max(result.pieces, static_cast<int>(map.size()));
    for (const PlacedPiece& p : map) shapes.insert(static_cast<int>(p.shape));
  }
  result.shapes = static_cast<int>(shapes.size());
  result.peak_reset = ResetPeakMemory();
  const auto start = std::chrono::steady_clock::now();
  StatusOr<object_learning::LearnedModel> model = object_learning::LearnObjects(series.maps, learn);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_rss_bytes = PeakMemoryBytes();
  if (!model.ok()) return model.status();
  result.score = ScoreAgainstPieces(series, *model, match_distance);
  result.num_objects = model->num_objects;
  result.num_templates = model->num_templates;
  result.searched = static_cast<int>(model->searched.size());
  result.warnings = model->warnings;
  result.estimated_mb = model->estimated_memory_mb;
  return result;
}

}  // namespace fleetmap::bench

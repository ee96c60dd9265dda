#include "bench/register/growing_experiment.hpp"

#include <fmt/format.h>

#include <chrono>
#include <numbers>
#include <random>

#include "common/core/number_format.hpp"
#include "common/registration/registration.hpp"

namespace fleetmap::bench {
namespace {

using registration::PlacementEvidence;

constexpr double kDegree = std::numbers::pi / 180.0;

// One rule fed the votes of a pair's steps in turn, as the placer feeds a robot's registrations.
class RuleRun {
 public:
  explicit RuleRun(const PlacementEvidence::Options& options) : evidence_(options) {}

  void Observe(int step, const PlacementEvidence::Vote& vote, bool right) {
    if (outcome_.placed_at > 0) return;
    if (evidence_.Observe(kKey, vote).place) outcome_ = {step, right};
  }
  const RuleOutcome& outcome() const { return outcome_; }

 private:
  inline static const registration::RegistrationKey kKey{RobotId{"b"}, {}};
  PlacementEvidence evidence_;
  RuleOutcome outcome_;
};

// Registers each step of B (the last is B itself) on A and feeds both rules.
GrowingPairOutcome RunSteps(const grid::OccupancyGrid& a,
                            const std::vector<grid::OccupancyGrid>& steps, const MapPair& truth,
                            const JudgePoint& at, const GrowingBenchOptions& options) {
  GrowingPairOutcome outcome;
  RuleRun bar_only(options.bar_only), sequential(options.sequential);
  for (size_t k = 0; k < steps.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    const StatusOr<registration::Registration> r =
        registration::Register(a, steps[k], options.pairs.registration);
    outcome.seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    PlacementEvidence::Vote vote;
    vote.map_changes = k + 1;
    vote.map_centre = KnownCentroid(steps[k]);
    MethodOutcome judged;
    if (r.ok()) {
      vote.target_from_map = r->a_from_b;
      vote.at_bar = r->found;
      vote.verified = r->verified;
      vote.confidence = r->confidence;
      vote.why_not = r->why_not;
      Judge(truth, at, r->a_from_b, options.pairs, &judged);
    }
    outcome.confidence.push_back(vote.confidence);
    outcome.verified.push_back(vote.verified ? 1 : 0);
    outcome.right.push_back(judged.right ? 1 : 0);
    outcome.error_cells.push_back(judged.translation_error_cells);
    outcome.score.push_back(r.ok() ? r->score : 0.0);
    outcome.overlap.push_back(r.ok() ? r->overlap : 0.0);
    outcome.peak_ratio.push_back(r.ok() ? r->peak_ratio : 0.0);
    bar_only.Observe(static_cast<int>(k) + 1, vote, judged.right);
    sequential.Observe(static_cast<int>(k) + 1, vote, judged.right);
  }
  outcome.bar_only = bar_only.outcome();
  outcome.sequential = sequential.outcome();
  return outcome;
}

void AddTo(const RuleOutcome& outcome, RuleSummary* summary, double* step_sum) {
  if (outcome.placed_at == 0) return;
  ++summary->placed;
  summary->wrong += !outcome.right;
  *step_sum += outcome.placed_at;
}

GrowingSummaryRow SummarizeRows(const std::string& group,
                                const std::vector<const GrowingPairOutcome*>& pairs) {
  GrowingSummaryRow row;
  row.group = group;
  double bar_steps = 0.0, sequential_steps = 0.0;
  for (const GrowingPairOutcome* p : pairs) {
    ++row.pairs;
    AddTo(p->bar_only, &row.bar_only, &bar_steps);
    AddTo(p->sequential, &row.sequential, &sequential_steps);
  }
  if (row.bar_only.placed > 0) row.bar_only.mean_step = bar_steps / row.bar_only.placed;
  if (row.sequential.placed > 0) {
    row.sequential.mean_step = sequential_steps / row.sequential.placed;
  }
  return row;
}

}  // namespace

GrowingBenchRun RunGrowingBench(const std::vector<SourceMap>& maps,
                                const GrowingBenchOptions& options, ProgressLine* progress) {
  GrowingBenchRun run;
  MapPairOptions pair_options = options.pairs.pairs;
  pair_options.growth_steps = options.steps;
  const size_t total = maps.size() * options.pairs.overlaps.size() *
                       static_cast<size_t>(std::max(0, options.pairs.pairs_per_overlap));
  size_t done = 0;
  const auto start = std::chrono::steady_clock::now();
  for (size_t m = 0; m < maps.size(); ++m) {
    for (size_t o = 0; o < options.pairs.overlaps.size(); ++o) {
      for (int k = 0; k < options.pairs.pairs_per_overlap; ++k) {
        ++done;
        // The pair bench's seeds: the full-grown B of a pair is that bench's B.
        std::seed_seq seq{options.pairs.seed, static_cast<uint32_t>(m), static_cast<uint32_t>(o),
                          static_cast<uint32_t>(k)};
        std::mt19937 rng(seq);
        StatusOr<MapPair> pair =
            MakeMapPair(maps[m].grid, options.pairs.overlaps[o], pair_options, rng);
        for (int retry = 0;
             retry < 4 && !pair.ok() && pair.status().code() == StatusCode::kNotFound; ++retry) {
          pair = MakeMapPair(maps[m].grid, options.pairs.overlaps[o], pair_options, rng);
        }
        if (!pair.ok()) {
          ++run.not_generated;
          continue;
        }
        std::vector<grid::OccupancyGrid> steps = pair->b_growing;
        steps.push_back(pair->b);
        const Point2 centroid_b = KnownCentroid(pair->b);
        GrowingPairOutcome plain =
            RunSteps(pair->a, steps, *pair, PlainJudgePoint(*pair, centroid_b), options);
        plain.map = maps[m].name;
        plain.group = maps[m].group;
        plain.target_overlap = options.pairs.overlaps[o];
        run.pairs.push_back(std::move(plain));
        if (options.pairs.drift) {
          // Every step warped alike: one robot's SLAM bends its growing map the same way.
          const DriftOptions& drift = options.pairs.drift_options;
          std::uniform_real_distribution<double> scale(-drift.max_scale, drift.max_scale);
          std::uniform_real_distribution<double> bend(-drift.max_bend_deg_per_m * kDegree,
                                                      drift.max_bend_deg_per_m * kDegree);
          const double s = scale(rng);
          const double b = bend(rng);
          for (grid::OccupancyGrid& step : steps) step = Warp(step, centroid_b, s, b);
          GrowingPairOutcome warped =
              RunSteps(pair->a, steps, *pair, DriftedJudgePoint(*pair, centroid_b, s, b), options);
          warped.map = maps[m].name;
          warped.group = maps[m].group + " drifted";
          warped.target_overlap = options.pairs.overlaps[o];
          run.pairs.push_back(std::move(warped));
        }
        if (progress != nullptr) {
          progress->Update(fmt::format(
              "bench register --growing: {}/{} pairs, {} s elapsed", done, total,
              static_cast<int>(
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                      .count())));
        }
      }
    }
  }
  if (progress != nullptr) progress->Finish();
  return run;
}

std::vector<GrowingSummaryRow> SummarizeGrowing(const std::vector<GrowingPairOutcome>& pairs) {
  std::vector<std::string> groups;
  for (const GrowingPairOutcome& p : pairs) {
    if (std::find(groups.begin(), groups.end(), p.group) == groups.end()) {
      groups.push_back(p.group);
    }
  }
  std::vector<GrowingSummaryRow> rows;
  std::vector<const GrowingPairOutcome*> every;
  for (const std::string& group : groups) {
    std::vector<const GrowingPairOutcome*> members;
    for (const GrowingPairOutcome& p : pairs) {
      if (p.group == group) members.push_back(&p);
    }
    rows.push_back(SummarizeRows(group, members));
  }
  for (const GrowingPairOutcome& p : pairs) every.push_back(&p);
  if (groups.size() > 1) rows.push_back(SummarizeRows("", every));
  return rows;
}

}  // namespace fleetmap::bench

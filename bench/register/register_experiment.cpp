#include "bench/register/register_experiment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include "bench/register/mexplore_registration.hpp"
#include "bench/register/repeated_terrain.hpp"
#include "bench/report/report_format.hpp"
#include "common/core/number_format.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::bench {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

MethodSummary SummarizeMethod(const std::vector<const MethodOutcome*>& outcomes) {
  MethodSummary s;
  std::vector<double> seconds;
  for (const MethodOutcome* o : outcomes) {
    ++s.pairs;
    s.found += o->found;
    s.successes += o->success;
    s.false_accepts += o->found && !o->success;
    seconds.push_back(o->seconds);
  }
  s.median_seconds = Median(seconds);
  s.worst_seconds = seconds.empty() ? 0.0 : *std::max_element(seconds.begin(), seconds.end());
  return s;
}

// A 30 m terrain at 5 cm cells: common/sim's kinds for k % 6 < 3 (unless repeated_only), the
// repeated ones otherwise.
StatusOr<SourceMap> TerrainMap(int k, uint32_t terrain_seed, bool repeated_only,
                               const std::string& group) {
  constexpr double kSize = 30.0;
  constexpr double kResolution = 0.05;
  const int kind = repeated_only ? 3 + k % kRepeatedKinds : k % 6;
  sim::Terrain terrain;
  std::string name;
  if (kind < 3) {
    constexpr sim::TerrainKind kKinds[] = {sim::TerrainKind::kOffice, sim::TerrainKind::kMaze,
                                           sim::TerrainKind::kUnstructured};
    sim::TerrainOptions terrain_options;
    terrain_options.kind = kKinds[kind];
    terrain_options.size = kSize;
    terrain_options.seed = terrain_seed;
    FLEETMAP_ASSIGN_OR_RETURN(const sim::TerrainGenerator generator,
                              sim::TerrainGenerator::Create(terrain_options));
    terrain = generator.Generate();
    name = sim::TerrainKindName(terrain_options.kind);
  } else {
    const auto repeated = static_cast<RepeatedKind>(kind - 3);
    terrain = RepeatedTerrain(repeated, kSize, terrain_seed);
    name = RepeatedKindName(repeated);
  }
  FLEETMAP_ASSIGN_OR_RETURN(grid::OccupancyGrid grid, sim::RasterizeTerrain(terrain, kResolution));
  name += "_";
  name += std::to_string(terrain_seed);
  return SourceMap{std::move(name), std::move(grid), group};
}

StatusOr<std::vector<SourceMap>> TerrainMaps(int count, uint32_t first_seed, bool repeated_only,
                                             const std::string& group) {
  std::vector<SourceMap> maps;
  for (int k = 0; k < count; ++k) {
    FLEETMAP_ASSIGN_OR_RETURN(
        SourceMap map, TerrainMap(k, first_seed + static_cast<uint32_t>(k), repeated_only, group));
    maps.push_back(std::move(map));
  }
  return maps;
}

// Registers one pair with both methods and judges them against the truth at `at`.
PairOutcome RegisterPair(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b,
                         const MapPair& truth, const JudgePoint& at,
                         const RegisterBenchOptions& options) {
  PairOutcome outcome;
  outcome.overlap = truth.overlap;
  outcome.a_cells = a.width() * a.height();
  outcome.b_cells = b.width() * b.height();
  auto t0 = std::chrono::steady_clock::now();
  const StatusOr<registration::Registration> r = registration::Register(a, b, options.registration);
  outcome.fleetmap.seconds = SecondsSince(t0);
  if (r.ok()) {
    outcome.fleetmap.found = r->found;
    outcome.fleetmap.confidence = r->confidence;
    outcome.fleetmap.score = r->score;
    outcome.fleetmap.why_not = r->why_not;
    outcome.fleetmap.agreeing_cells = r->agreeing_cells;
    outcome.fleetmap.contradicting_cells = r->contradicting_cells;
    outcome.fleetmap.peak_ratio = r->peak_ratio;
    for (size_t k = 0; k < r->finalists.size() && outcome.fleetmap.right_finalist < 0; ++k) {
      MethodOutcome finalist;
      Judge(truth, at, r->finalists[k], options, &finalist);
      if (finalist.right) outcome.fleetmap.right_finalist = static_cast<int>(k);
    }
    Judge(truth, at, r->a_from_b, options, &outcome.fleetmap);
  }
  if (options.run_mexplore) {
    t0 = std::chrono::steady_clock::now();
    const MexploreRegistration mx = RegisterLikeMexplore(a, b);
    outcome.mexplore.seconds = SecondsSince(t0);
    outcome.mexplore.found = mx.found;
    outcome.mexplore.confidence = mx.match_confidence;
    Judge(truth, at, mx.a_from_b, options, &outcome.mexplore);
  }
  return outcome;
}

}  // namespace

JudgePoint PlainJudgePoint(const MapPair& pair, const Point2& centroid_b) {
  return {centroid_b, pair.a_from_b * centroid_b, Pose2::FromTransform(pair.a_from_b).yaw};
}

JudgePoint DriftedJudgePoint(const MapPair& pair, const Point2& pivot, double scale,
                             double bend_per_metre) {
  const Point2 overlap = OverlapCentroid(pair);
  const WarpedPoint warped = WarpPoint(pair.b, pivot, scale, bend_per_metre, overlap);
  return {warped.point, pair.a_from_b * overlap,
          Pose2::FromTransform(pair.a_from_b).yaw - warped.turn};
}

void Judge(const MapPair& pair, const JudgePoint& at, const Pose2& estimate,
           const RegisterBenchOptions& options, MethodOutcome* outcome) {
  const Point2 d = estimate.ToTransform() * at.b - at.a;
  outcome->translation_error_cells = d.norm() / pair.b.resolution();
  outcome->yaw_error_deg = std::abs(NormalizeAngle(estimate.yaw - at.yaw)) / kDegree;
  outcome->right = outcome->translation_error_cells <= options.max_translation_cells &&
                   outcome->yaw_error_deg <= options.max_yaw_deg;
  outcome->success = outcome->found && outcome->right;
}

StatusOr<std::vector<SourceMap>> SyntheticSourceMaps(int count, uint32_t seed) {
  return TerrainMaps(count, seed * 7919u, false, "synthetic");
}

StatusOr<std::vector<SourceMap>> RepeatedSourceMaps(int count, uint32_t seed) {
  return TerrainMaps(count, 1'000'000u + seed * 7919u, true, "repeated");
}

RegisterBenchRun RunRegisterBench(const std::vector<SourceMap>& maps,
                                  const RegisterBenchOptions& options, ProgressLine* progress) {
  RegisterBenchRun run;
  const auto start = std::chrono::steady_clock::now();
  const size_t total = maps.size() * options.overlaps.size() *
                       static_cast<size_t>(std::max(0, options.pairs_per_overlap));
  size_t done = 0;
  for (size_t m = 0; m < maps.size(); ++m) {
    for (size_t o = 0; o < options.overlaps.size(); ++o) {
      for (int k = 0; k < options.pairs_per_overlap; ++k) {
        ++done;
        // Each pair has its own generator, so a pair does not depend on which others were made.
        std::seed_seq seq{options.seed, static_cast<uint32_t>(m), static_cast<uint32_t>(o),
                          static_cast<uint32_t>(k)};
        std::mt19937 rng(seq);
        StatusOr<MapPair> pair = MakeMapPair(maps[m].grid, options.overlaps[o], options.pairs, rng);
        for (int retry = 0;
             retry < 4 && !pair.ok() && pair.status().code() == StatusCode::kNotFound; ++retry) {
          pair = MakeMapPair(maps[m].grid, options.overlaps[o], options.pairs, rng);
        }
        if (!pair.ok()) {
          ++run.not_generated;
          if (progress != nullptr) {
            progress->Print(fmt::format("bench register: {} overlap {}: {}", maps[m].name,
                                        ShortNumber(options.overlaps[o]), pair.status().message()));
          }
          continue;
        }
        const Point2 centroid_b = KnownCentroid(pair->b);
        PairOutcome outcome =
            RegisterPair(pair->a, pair->b, *pair, PlainJudgePoint(*pair, centroid_b), options);
        outcome.map = maps[m].name;
        outcome.group = maps[m].group;
        outcome.target_overlap = options.overlaps[o];
        run.pairs.push_back(outcome);
        if (options.drift) {
          // The same pair with B warped about its known centroid, judged where it overlaps A
          // (drawn after the pair, so the plain pairs do not depend on whether drift is on).
          std::uniform_real_distribution<double> scale(-options.drift_options.max_scale,
                                                       options.drift_options.max_scale);
          std::uniform_real_distribution<double> bend(
              -options.drift_options.max_bend_deg_per_m * kDegree,
              options.drift_options.max_bend_deg_per_m * kDegree);
          const double s = scale(rng);
          const double b = bend(rng);
          const grid::OccupancyGrid drifted = Warp(pair->b, centroid_b, s, b);
          PairOutcome warped = RegisterPair(pair->a, drifted, *pair,
                                            DriftedJudgePoint(*pair, centroid_b, s, b), options);
          warped.map = maps[m].name;
          warped.group = maps[m].group + " drifted";
          warped.target_overlap = options.overlaps[o];
          run.pairs.push_back(warped);
        }
        if (progress != nullptr) {
          progress->Update(fmt::format("bench register: {}/{} pairs, {} s elapsed", done, total,
                                       static_cast<int>(SecondsSince(start))));
        }
      }
    }
  }
  if (progress != nullptr) progress->Finish();
  return run;
}

std::vector<SummaryRow> Summarize(const std::vector<PairOutcome>& pairs) {
  std::vector<std::string> groups;
  std::vector<double> targets;
  for (const PairOutcome& p : pairs) {
    if (std::find(groups.begin(), groups.end(), p.group) == groups.end()) {
      groups.push_back(p.group);
    }
    if (std::find(targets.begin(), targets.end(), p.target_overlap) == targets.end()) {
      targets.push_back(p.target_overlap);
    }
  }
  std::sort(targets.begin(), targets.end());
  targets.push_back(-1.0);  // all of the group's pairs
  const auto row = [&pairs](const std::string* group, double target) {
    SummaryRow out;
    out.group = group != nullptr ? *group : std::string();
    out.target_overlap = target;
    std::vector<const MethodOutcome*> fleetmap, mexplore;
    double overlap_sum = 0.0;
    for (const PairOutcome& p : pairs) {
      if (group != nullptr && p.group != *group) continue;
      if (target >= 0.0 && p.target_overlap != target) continue;
      fleetmap.push_back(&p.fleetmap);
      mexplore.push_back(&p.mexplore);
      overlap_sum += p.overlap;
    }
    out.mean_overlap = fleetmap.empty() ? 0.0 : overlap_sum / fleetmap.size();
    out.fleetmap = SummarizeMethod(fleetmap);
    out.mexplore = SummarizeMethod(mexplore);
    return out;
  };
  std::vector<SummaryRow> rows;
  for (const std::string& group : groups) {
    for (const double target : targets) rows.push_back(row(&group, target));
  }
  if (groups.size() > 1) rows.push_back(row(nullptr, -1.0));
  return rows;
}

std::vector<ReliabilityBin> Reliability(const std::vector<PairOutcome>& pairs) {
  std::vector<ReliabilityBin> bins;
  const std::vector<double> edges = {0.0, 0.5, 0.8, 0.9, 0.95, 0.99, 1.0};
  for (size_t i = 0; i + 1 < edges.size(); ++i) bins.push_back({edges[i], edges[i + 1], 0, 0, 0.0});
  for (const PairOutcome& p : pairs) {
    if (!p.fleetmap.found) continue;
    const double c = p.fleetmap.confidence;
    for (size_t i = 0; i < bins.size(); ++i) {
      const bool last = i + 1 == bins.size();
      if (c >= bins[i].lo && (c < bins[i].hi || last)) {
        ++bins[i].found;
        bins[i].correct += p.fleetmap.success;
        bins[i].mean_confidence += c;
        break;
      }
    }
  }
  for (ReliabilityBin& b : bins) {
    if (b.found > 0) b.mean_confidence /= b.found;
  }
  return bins;
}

double ExpectedCalibrationError(const std::vector<ReliabilityBin>& bins) {
  int found = 0;
  for (const ReliabilityBin& b : bins) found += b.found;
  if (found == 0) return 0.0;
  double error = 0.0;
  for (const ReliabilityBin& b : bins) {
    if (b.found == 0) continue;
    error += static_cast<double>(b.found) / found *
             std::abs(static_cast<double>(b.correct) / b.found - b.mean_confidence);
  }
  return error;
}

}  // namespace fleetmap::bench

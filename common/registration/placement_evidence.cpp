#include "common/registration/placement_evidence.hpp"

#include <fmt/format.h>

#include <cmath>

namespace fleetmap::registration {

PlacementEvidence::Verdict PlacementEvidence::Observe(const RegistrationKey& key,
                                                      const Vote& vote) {
  Verdict verdict;
  const bool sequential = options_.sequential_wins > 0;
  const bool supports = vote.at_bar || (sequential && vote.verified &&
                                        vote.confidence >= options_.sequential_confidence);
  if (!supports) {
    leaders_.erase(key);
    verdict.why = vote.why_not;
    return verdict;
  }
  auto [it, inserted] = leaders_.try_emplace(key);
  Leader& leader = it->second;
  if (!inserted && !Same(leader.target_from_map, vote.target_from_map, vote.map_centre)) {
    verdict.why =
        "the best placement moved since the last registration (repeated structure "
        "or a map still too small): counting again; ";
    leader = Leader{};
    inserted = true;
  }
  leader.target_from_map = vote.target_from_map;
  if (vote.at_bar) ++leader.streak;
  // The same map registered again says nothing new: only a grown map adds a win.
  if (inserted || vote.map_changes != leader.map_changes) {
    ++leader.wins;
    leader.map_changes = vote.map_changes;
  }
  verdict.streak = leader.streak;
  verdict.wins = leader.wins;
  verdict.place = leader.streak >= options_.confirmations ||
                  (sequential && leader.wins >= options_.sequential_wins);
  if (verdict.place) {
    leaders_.erase(it);
    verdict.why.clear();
    return verdict;
  }
  if (vote.at_bar) {
    verdict.why += fmt::format(
        "found at confidence {:.2f}; waiting for {} more registration(s) of its growing map to "
        "find the same placement",
        vote.confidence, options_.confirmations - leader.streak);
  } else {
    verdict.why += fmt::format(
        "{}; the same placement verified {} time(s) in a row at {:.2f} or more: waiting for {} "
        "more registration(s) of its growing map to find it",
        vote.why_not, leader.wins, options_.sequential_confidence,
        options_.sequential_wins - leader.wins);
  }
  return verdict;
}

bool PlacementEvidence::Pending(const RegistrationKey& key) const {
  const auto leader = leaders_.find(key);
  return leader != leaders_.end() && leader->second.streak > 0;
}

void PlacementEvidence::Forget(const RobotId& robot) {
  std::erase_if(leaders_, [&](const auto& entry) { return entry.first.robot == robot; });
}

bool PlacementEvidence::Same(const Pose2& a, const Pose2& b, const Point2& centre) const {
  const Point2 at_a = a.ToTransform() * centre;
  const Point2 at_b = b.ToTransform() * centre;
  const double yaw_deg = std::abs(NormalizeAngle(a.yaw - b.yaw)) * 180.0 / M_PI;
  return (at_a - at_b).norm() <= options_.same_distance && yaw_deg <= options_.same_yaw_deg;
}

}  // namespace fleetmap::registration

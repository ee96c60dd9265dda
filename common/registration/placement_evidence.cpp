#include "common/registration/placement_evidence.hpp"

#include <fmt/format.h>

#include <cmath>

namespace fleetmap::registration {

PlacementEvidence::Verdict PlacementEvidence::Observe(const RegistrationKey& key,
                                                      const Vote& vote) {
  Verdict verdict;
  if (!vote.at_bar) {
    leaders_.erase(key);
    verdict.why = vote.why_not;
    return verdict;
  }
  auto [it, inserted] = leaders_.try_emplace(key);
  Leader& leader = it->second;
  if (inserted || !Same(leader.target_from_map, vote.target_from_map, vote.map_centre)) {
    if (!inserted) {
      verdict.why =
          "the best placement moved since the last registration (repeated structure "
          "or a map still too small): counting again; ";
    }
    leader.streak = 0;
  }
  leader.target_from_map = vote.target_from_map;
  ++leader.streak;
  verdict.streak = leader.streak;
  verdict.place = leader.streak >= options_.confirmations;
  if (verdict.place) {
    leaders_.erase(it);
    verdict.why.clear();
  } else {
    verdict.why += fmt::format(
        "found at confidence {:.2f}; waiting for {} more registration(s) of its growing map to "
        "find the same placement",
        vote.confidence, options_.confirmations - leader.streak);
  }
  return verdict;
}

bool PlacementEvidence::Pending(const RegistrationKey& key) const {
  return leaders_.count(key) > 0;
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

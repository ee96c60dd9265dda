#include "common/registration/placement_groups.hpp"

#include <deque>

namespace fleetmap::registration {

PlacementGroup GroupOf(const RobotId& robot, const std::vector<RobotLink>& links,
                       const std::set<RobotId>& excluded) {
  // Breadth first from `robot`, in its frame; then re-expressed in the root's.
  std::map<RobotId, Transform2> start_from;
  start_from.emplace(robot, Transform2::Identity());
  std::deque<RobotId> to_visit = {robot};
  while (!to_visit.empty()) {
    const RobotId at = to_visit.front();
    to_visit.pop_front();
    const Transform2 start_from_at = start_from.at(at);
    for (const RobotLink& link : links) {
      RobotId other;
      Transform2 at_from_other;
      if (link.robot == at) {
        other = link.leader;
        at_from_other = link.leader_from_map.ToTransform().inverse();
      } else if (link.leader == at) {
        other = link.robot;
        at_from_other = link.leader_from_map.ToTransform();
      } else {
        continue;
      }
      if (excluded.count(other) > 0 || start_from.count(other) > 0) continue;
      start_from.emplace(other, start_from_at * at_from_other);
      to_visit.push_back(other);
    }
  }
  PlacementGroup group;
  group.root = start_from.begin()->first;  // the smallest id: the same root from every member
  const Transform2 root_from_start = start_from.begin()->second.inverse();
  for (const auto& [member, start_from_member] : start_from) {
    group.root_from_member[member] = Pose2::FromTransform(root_from_start * start_from_member);
  }
  return group;
}

}  // namespace fleetmap::registration

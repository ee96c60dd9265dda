#pragma once

#include <map>
#include <set>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/types.hpp"

namespace fleetmap::registration {

// Where one unplaced robot's map sits in another's, found by registering the two maps.
struct RobotLink {
  RobotId robot;
  RobotId leader;
  Pose2 leader_from_map;  // takes the robot's map frame into the leader's
};

// Unplaced robots registered to each other, as one rigid group: its root (the member with the
// smallest id) and where every member's map frame sits in the root's (the root's own is the
// identity). A robot without links is a group of one.
struct PlacementGroup {
  RobotId root;
  std::map<RobotId, Pose2> root_from_member;

  bool alone() const { return root_from_member.size() <= 1; }
};

// The group `robot` belongs to: the robots `links` connect it to (either way), leaving out
// `excluded` ones (placed robots: they are the fleet's, not the group's). Members reached by
// more than one path keep the first transform found (breadth first, links in order).
PlacementGroup GroupOf(const RobotId& robot, const std::vector<RobotLink>& links,
                       const std::set<RobotId>& excluded);

}  // namespace fleetmap::registration

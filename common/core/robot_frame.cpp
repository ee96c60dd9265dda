#include "common/core/robot_frame.hpp"

namespace fleetmap {

const char* RobotFrameStateName(RobotFrame::State state) {
  switch (state) {
    case RobotFrame::State::kUnplaced:
      return "unplaced";
    case RobotFrame::State::kPlaced:
      return "placed";
    case RobotFrame::State::kRevised:
      return "revised";
    case RobotFrame::State::kGiven:
      return "given";
    case RobotFrame::State::kAnchor:
      return "anchor";
  }
  return "unknown";
}

const char* RobotStandingName(RobotFrame::Standing standing) {
  switch (standing) {
    case RobotFrame::Standing::kTrusted:
      return "trusted";
    case RobotFrame::Standing::kQuarantined:
      return "quarantined";
    case RobotFrame::Standing::kAdmitted:
      return "admitted";
  }
  return "unknown";
}

}  // namespace fleetmap

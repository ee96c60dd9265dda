#pragma once

// Internal to transport: a DDS content filter for the keyed topics whose first field is a robot
// id (rt/fleetmap/robot_status, rt/fleetmap/robot_frames). A reader that wants one robot's
// instances only (an agent: claims of its own id, its own frame) names the robot; every fleetmap
// participant registers the filter class, so the writers' participants evaluate it and send such
// a reader nothing else (Fast DDS writer-side content filtering). An agent then costs a fleet of N
// robots (or a flood of ids) nothing per other robot. A writer of another vendor sends
// everything, and the reader's own participant filters on arrival.
//
// The filter reads the serialized sample: the CDR string that starts it. A sample it cannot read
// (a disposal carrying no payload) passes: the reader decides, as without a filter.

#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>

#include <optional>
#include <string>
#include <string_view>

namespace fleetmap::transport {

inline constexpr const char* kRobotIdFilterClass = "FLEETMAP_ROBOT_ID";
inline constexpr const char* kRobotIdFilterExpression = "robot_id = %0";

// The factory every Participant registers under kRobotIdFilterClass; process-wide, never deleted
// (Fast DDS keeps the pointer for the participants' lifetime).
eprosima::fastdds::dds::IContentFilterFactory& RobotIdFilterFactory();

// The string a CDR sample starts with (after its 4-byte encapsulation header), or nullopt when
// the payload is too short or the string's length or terminator is not what CDR says.
std::optional<std::string_view> LeadingCdrString(
    const eprosima::fastrtps::rtps::SerializedPayload_t& payload);

}  // namespace fleetmap::transport

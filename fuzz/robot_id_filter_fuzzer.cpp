// Fuzz target: the robot-id content filter (common/transport/internal/robot_id_filter.hpp). Every
// fleetmap participant registers it, so a writer's participant runs it on every sample it sends
// to a filtered reader, and a reader's participant on every sample another vendor's writer sends:
// the serialized payload is whatever the writer made. The first byte picks the robot the filter
// was made for; the rest is the payload.
//
// Besides crashes, two properties: a leading string it reads lies inside the payload, after the
// encapsulation header and the length; and the filter passes exactly the samples that name its
// robot or whose robot it cannot read (the reader decides on those, as without a filter).

#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastdds/dds/core/StackAllocatedSequence.hpp>
#include <fastdds/dds/topic/IContentFilter.hpp>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "common/core/check.hpp"
#include "common/transport/internal/robot_id_filter.hpp"

namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::SerializedPayload_t;

// The robots a filter may be made for: a usual name, an empty one, one with a quote inside.
constexpr const char* kRobots[] = {"'alpha'", "alpha", "''", "'robot_0'", "'a''b'"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const char* parameter = kRobots[data[0] % (sizeof(kRobots) / sizeof(kRobots[0]))];
  SerializedPayload_t payload(static_cast<uint32_t>(size - 1));
  if (size > 1) std::memcpy(payload.data, data + 1, size - 1);
  payload.length = static_cast<uint32_t>(size - 1);

  const std::optional<std::string_view> robot = fleetmap::transport::LeadingCdrString(payload);
  if (robot) {
    const auto* first = reinterpret_cast<const uint8_t*>(robot->data());
    FLEETMAP_CHECK(first == payload.data + 8, "the leading string starts after header and length");
    FLEETMAP_CHECK(robot->size() + 9 <= payload.length, "the leading string ends in the payload");
  }

  dds::IContentFilterFactory& factory = fleetmap::transport::RobotIdFilterFactory();
  eprosima::fastdds::dds::StackAllocatedSequence<const char*, 1> parameters;
  parameters.length(1);
  parameters[0] = parameter;
  dds::IContentFilter* filter = nullptr;
  const auto created = factory.create_content_filter(
      fleetmap::transport::kRobotIdFilterClass, "fleetmap_msgs::msg::dds_::RobotStatus_", nullptr,
      fleetmap::transport::kRobotIdFilterExpression, parameters, filter);
  FLEETMAP_CHECK(
      created == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK && filter != nullptr,
      "the filter is made for any robot name");
  const bool passed = filter->evaluate(payload, dds::IContentFilter::FilterSampleInfo(),
                                       eprosima::fastrtps::rtps::GUID_t());
  std::string name(parameter);
  if (name.size() >= 2 && name.front() == '\'' && name.back() == '\'') {
    name = name.substr(1, name.size() - 2);
  }
  FLEETMAP_CHECK(passed == (!robot || *robot == name),
                 "the filter passes its robot's samples and the ones it cannot read");
  factory.delete_content_filter(fleetmap::transport::kRobotIdFilterClass, filter);
  return 0;
}

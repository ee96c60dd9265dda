#include "common/transport/internal/robot_id_filter.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace fleetmap::transport {
namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

// A sample as CDR: the encapsulation header, then a string (length with its NUL), then `tail`.
SerializedPayload_t Payload(bool little_endian, const std::string& text, uint32_t length,
                            bool terminated = true) {
  std::vector<uint8_t> bytes = {0x00, static_cast<uint8_t>(little_endian ? 0x01 : 0x00), 0, 0};
  for (int i = 0; i < 4; ++i) {
    const int shift = little_endian ? 8 * i : 8 * (3 - i);
    bytes.push_back(static_cast<uint8_t>(length >> shift));
  }
  bytes.insert(bytes.end(), text.begin(), text.end());
  if (terminated) bytes.push_back(0);
  bytes.insert(bytes.end(), {7, 7, 7, 7});  // the fields after it
  SerializedPayload_t payload(static_cast<uint32_t>(bytes.size()));
  std::copy(bytes.begin(), bytes.end(), payload.data);
  payload.length = static_cast<uint32_t>(bytes.size());
  return payload;
}

TEST(LeadingCdrStringTest, ReadsTheStringASampleStartsWithInEitherByteOrder) {
  EXPECT_EQ(LeadingCdrString(Payload(true, "alpha", 6)), "alpha");
  EXPECT_EQ(LeadingCdrString(Payload(false, "robot_7", 8)), "robot_7");
}

TEST(LeadingCdrStringTest, RefusesWhatIsNotACdrString) {
  EXPECT_EQ(LeadingCdrString(SerializedPayload_t()), std::nullopt);             // no payload
  EXPECT_EQ(LeadingCdrString(Payload(true, "alpha", 0)), std::nullopt);         // no NUL counted
  EXPECT_EQ(LeadingCdrString(Payload(true, "alpha", 4000)), std::nullopt);      // past the end
  EXPECT_EQ(LeadingCdrString(Payload(true, "alpha", 6, false)), std::nullopt);  // no NUL there
}

}  // namespace
}  // namespace fleetmap::transport

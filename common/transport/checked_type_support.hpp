#pragma once

// Internal to transport: a generated PubSubType that checks each received payload against its
// CDR shape before fastcdr decodes it (see cdr_shape.hpp), so a hostile or corrupt sample is
// refused instead of making the reader allocate whatever its lengths claim.

#include <fastdds/rtps/common/SerializedPayload.h>

#include <functional>
#include <span>
#include <utility>

#include "common/transport/cdr_shape.hpp"

namespace fleetmap::transport {

template <typename GeneratedPubSubType>
class CheckedPubSubType : public GeneratedPubSubType {
 public:
  // `on_reject` runs on the DDS thread that received the sample; it must only queue.
  CheckedPubSubType(const CdrShape& shape, std::function<void(const Status&)> on_reject)
      : shape_(shape), on_reject_(std::move(on_reject)) {}

  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    const Status checked =
        CheckCdr(std::span<const uint8_t>(payload->data, payload->length), shape_);
    if (!checked.ok()) {
      if (on_reject_) on_reject_(checked);
      return false;
    }
    return GeneratedPubSubType::deserialize(payload, data);
  }

 private:
  const CdrShape& shape_;
  std::function<void(const Status&)> on_reject_;
};

}  // namespace fleetmap::transport

#pragma once

// Internal to transport: the type support of every wire type. Each is the generated PubSubType
// with one addition: a received payload is checked against the type's CDR shape before fastcdr
// decodes it (see cdr_shape.hpp), so a hostile or corrupt sample is refused instead of making the
// reader allocate whatever its lengths claim.
//
// A participant registers a type name once and every reader and writer of that name shares the
// registration, so all of them must use these factories. Fast DDS decodes a sample inside
// take_next_sample(), on the listener's own thread: a listener names itself the receiver of
// refusals with a ScopedMalformedSink around its take loop.

#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <span>

#include "common/core/status.hpp"
#include "common/transport/cdr_shape.hpp"

namespace fleetmap::transport {

// Receives the payloads refused on a listener's thread.
class MalformedSink {
 public:
  virtual ~MalformedSink() = default;
  void Refuse(const Status& error) {
    ++refused_;
    OnMalformed(error);
  }
  uint64_t refused() const { return refused_; }

 protected:
  virtual void OnMalformed(const Status& error) = 0;

 private:
  uint64_t refused_ = 0;  // the listener's thread only
};

// Routes refusals on this thread to `sink` while it lives.
class ScopedMalformedSink {
 public:
  explicit ScopedMalformedSink(MalformedSink* sink);
  ~ScopedMalformedSink();
  ScopedMalformedSink(const ScopedMalformedSink&) = delete;
  ScopedMalformedSink& operator=(const ScopedMalformedSink&) = delete;

  static MalformedSink* Current();

 private:
  MalformedSink* previous_;
};

template <typename GeneratedPubSubType>
class CheckedPubSubType : public GeneratedPubSubType {
 public:
  explicit CheckedPubSubType(const CdrShape& shape) : shape_(shape) {}

  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    const Status checked =
        CheckCdr(std::span<const uint8_t>(payload->data, payload->length), shape_);
    if (!checked.ok()) {
      if (MalformedSink* sink = ScopedMalformedSink::Current()) sink->Refuse(checked);
      return false;
    }
    return GeneratedPubSubType::deserialize(payload, data);
  }

 private:
  const CdrShape& shape_;
};

// Takes every sample `reader` holds and hands each valid one to `handle(sample, info)`, with
// refusals going to `sink`. A refused payload does not end the loop; an empty reader does.
template <typename Sample, typename Handle>
void TakeAll(eprosima::fastdds::dds::DataReader* reader, MalformedSink* sink, Handle handle) {
  constexpr int kMaxTakes = 100000;  // a bound, so a misbehaving reader cannot spin forever
  Sample sample;
  eprosima::fastdds::dds::SampleInfo info;
  const ScopedMalformedSink scope(sink);
  for (int i = 0; i < kMaxTakes; ++i) {
    const uint64_t refused_before = sink->refused();
    if (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      handle(sample, info);
    } else if (sink->refused() == refused_before) {
      return;
    }
  }
}

eprosima::fastdds::dds::TypeSupport RobotStatusTypeSupport();
eprosima::fastdds::dds::TypeSupport OccupancyGridTypeSupport();
eprosima::fastdds::dds::TypeSupport OccupancyGridUpdateTypeSupport();
eprosima::fastdds::dds::TypeSupport VectorTileTypeSupport();
eprosima::fastdds::dds::TypeSupport EntityTypeSupport();
eprosima::fastdds::dds::TypeSupport SubmapTypeSupport();
eprosima::fastdds::dds::TypeSupport ObjectTemplateTypeSupport();
eprosima::fastdds::dds::TypeSupport ObjectModelTypeSupport();

}  // namespace fleetmap::transport

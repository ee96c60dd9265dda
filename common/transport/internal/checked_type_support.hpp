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
#include <fastdds/dds/core/LoanableSequence.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <span>

#include "common/core/status.hpp"
#include "common/transport/internal/cdr_shape.hpp"

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
    // Fast DDS also decodes on its receive thread (to hash a key the writer did not send), where
    // no listener's guard is around: nothing may escape from here.
    try {
      return GeneratedPubSubType::deserialize(payload, data);
    } catch (const std::exception& error) {
      if (MalformedSink* sink = ScopedMalformedSink::Current()) {
        sink->Refuse(InvalidArgumentError(std::string("payload does not decode: ") + error.what()));
      }
      return false;
    }
  }

  // The generated key serializer writes into a buffer sized for keys of at most 255 characters
  // and throws on a longer one, on a Fast DDS thread where nothing catches it: the process would
  // abort. Fast DDS 2.9 also ignores getKey's result on the receiving side and asserts later on a
  // sample left without an instance. So a key that cannot be hashed gets one fixed handle of its
  // own: such samples share one instance, and the reader's checks then refuse them by content
  // (no valid robot id is that long).
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle,
              bool force_md5) override {
    try {
      return GeneratedPubSubType::getKey(data, handle, force_md5);
    } catch (...) {
      static constexpr char kUnhashable[] = "fleetmap:unhash";  // 15 characters and a NUL
      for (size_t i = 0; i < sizeof(kUnhashable); ++i) {
        handle->value[i] = static_cast<eprosima::fastrtps::rtps::octet>(kUnhashable[i]);
      }
      return true;
    }
  }

 private:
  const CdrShape& shape_;
};

// Runs `callback` on a DDS listener thread so that nothing it throws escapes into Fast DDS,
// where an exception terminates the process: whatever a peer sends, the receiver survives. What
// was thrown goes to `sink` as a refusal.
template <typename Callback>
void GuardListener(MalformedSink* sink, const char* what, Callback callback) noexcept {
  try {
    callback();
  } catch (const std::exception& error) {
    try {
      sink->Refuse(InternalError(std::string(what) + " failed: " + error.what()));
    } catch (...) {
    }
  } catch (...) {
    try {
      sink->Refuse(InternalError(std::string(what) + " failed"));
    } catch (...) {
    }
  }
}

// Takes every sample `reader` holds and hands each valid one to `handle(sample, info)`, with
// refusals going to `sink`. A refused payload does not end the loop (Fast DDS drops it from the
// history); an empty reader does. A sample whose handling throws is refused, and the loop goes on.
//
// Samples are taken in batches, never one by one: Fast DDS 2.9 looks for the next sample from
// the first instance on, visiting every change it holds back (those after a gap, waiting for a
// repair), so take_next_sample() in a loop costs samples x instances. A flood of thousands of
// keys over a lossy link made that the server's busiest thread.
template <typename Sample, typename Handle>
void TakeAll(eprosima::fastdds::dds::DataReader* reader, MalformedSink* sink, Handle handle) {
  constexpr int kBatch = 32;         // Fast DDS's default max_samples_per_read
  constexpr int kMaxBatches = 4096;  // a bound, so a misbehaving reader cannot spin forever
  eprosima::fastdds::dds::LoanableSequence<Sample> samples(kBatch);
  eprosima::fastdds::dds::SampleInfoSeq infos(kBatch);
  const ScopedMalformedSink scope(sink);
  for (int batch = 0; batch < kMaxBatches; ++batch) {
    const uint64_t refused_before = sink->refused();
    bool taken = false;
    GuardListener(sink, "taking samples", [&] {
      taken = reader->take(samples, infos, kBatch) == ReturnCode_t::RETCODE_OK;
    });
    if (taken) {
      for (eprosima::fastdds::dds::LoanableCollection::size_type i = 0; i < samples.length(); ++i) {
        GuardListener(sink, "handling a sample", [&] { handle(samples[i], infos[i]); });
      }
    }
    if (!taken && sink->refused() == refused_before) return;
  }
}

eprosima::fastdds::dds::TypeSupport RobotStatusTypeSupport();
eprosima::fastdds::dds::TypeSupport OccupancyGridTypeSupport();
eprosima::fastdds::dds::TypeSupport OccupancyGridUpdateTypeSupport();
eprosima::fastdds::dds::TypeSupport CompressedGridUpdateTypeSupport();
eprosima::fastdds::dds::TypeSupport VectorTileTypeSupport();
eprosima::fastdds::dds::TypeSupport EntityTypeSupport();
eprosima::fastdds::dds::TypeSupport SubmapTypeSupport();
eprosima::fastdds::dds::TypeSupport ObjectTemplateTypeSupport();
eprosima::fastdds::dds::TypeSupport ObjectModelTypeSupport();
eprosima::fastdds::dds::TypeSupport RobotFrameTypeSupport();
eprosima::fastdds::dds::TypeSupport RobotAdmissionTypeSupport();
eprosima::fastdds::dds::TypeSupport FleetServerTypeSupport();
eprosima::fastdds::dds::TypeSupport RouteGraphTypeSupport();
eprosima::fastdds::dds::TypeSupport TfMessageTypeSupport();

}  // namespace fleetmap::transport

#include "common/transport/vector_tile_reader.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <map>
#include <mutex>
#include <optional>

#include "common/core/fair_sample_queue.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"
#include "common/transport/internal/writer_id.hpp"
#include "common/transport/topics.hpp"
#include "fleetmap_msgs/msg/VectorTile.h"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;
using fleetmap_msgs::msg::dds_::VectorTile_;

// Runs on DDS threads: takes and queues, nothing more. Decoding waits for Drain(), on the owner's
// thread: a DDS receive thread serves every writer on its port (and, on the server, the
// liveliness of every robot), so no writer's tiles, however heavy, may hold it up.
class VectorTileReader::Listener : public dds::DataReaderListener, public MalformedSink {
 public:
  Listener(const Participant& participant, std::string topic_name, std::shared_ptr<WakeUp> wake_up,
           const TileDecodeLimits& limits)
      : participant_(participant),
        topic_name_(std::move(topic_name)),
        wake_up_(std::move(wake_up)),
        limits_(limits),
        received_(kQueueCapacity) {}

  void on_data_available(dds::DataReader* reader) override {
    TakeAll<VectorTile_>(
        reader, this, [this](const VectorTile_& sample, const dds::SampleInfo& info) {
          Received received;
          received.event.writer = WriterId(info.publication_handle);
          received.event.host = participant_.HostOf(received.event.writer).value_or("");
          received.event.received = Clock::now();
          if (info.valid_data) {
            OnSample(sample, info, std::move(received));
          } else {
            OnInstanceGone(info, std::move(received.event));
          }
        });
    Notify();
  }

  std::vector<TileEvent> Drain(size_t max_events) {
    std::vector<TileEvent> events;
    for (Received& received : received_.Drain(max_events)) {
      if (received.sample) Decode(*received.sample, &received.event);
      events.push_back(std::move(received.event));
    }
    return events;
  }
  size_t DrainCount() {
    size_t tiles = 0;
    for (const Received& received : received_.Drain()) tiles += received.sample ? 1 : 0;
    return tiles;
  }
  size_t queued() const { return received_.size(); }
  size_t dropped() const { return received_.dropped(); }

 protected:
  void OnMalformed(const Status& error) override {
    Received received;
    received.event.kind = TileEvent::Kind::kRejected;
    received.event.error = error.WithContext(topic_name_ + ": malformed VectorTile payload");
    received_.Push(std::string(), std::move(received));
  }

 private:
  // Samples waiting for Drain(), of all writers: about 80 MB of heavy 10 KB tiles. Past it the
  // participant holding the most loses its oldest (FairSampleQueue).
  static constexpr size_t kQueueCapacity = 8192;

  // A sample taken, or an event complete without one (a disposal, a malformed payload).
  struct Received {
    TileEvent event;
    std::optional<VectorTile_> sample;  // still to decode
  };

  void OnSample(const VectorTile_& sample, const dds::SampleInfo& info, Received received) {
    if (IsValidRobotName(sample.robot_id()) || sample.robot_id() == "fleet") {
      // The instance's key, for its disposal: read from the sample without decoding it.
      std::lock_guard lock(mutex_);
      key_by_instance_[info.instance_handle] = {RobotId{sample.robot_id()},
                                                TileId{sample.tile_x(), sample.tile_y()}};
    }
    received.event.serialized_bytes = VectorTile_::getCdrSerializedSize(sample) + 4;
    received.sample = sample;
    Push(std::move(received));
  }

  // Decodes a taken sample into `event` (kTile), or says why not (kRejected).
  void Decode(const VectorTile_& sample, TileEvent* event) const {
    StatusOr<VectorTileMessage> tile = FromIdl(sample, limits_);
    if (!tile.ok()) {
      event->kind = TileEvent::Kind::kRejected;
      // Name the robot when the name itself is sound, so the server can count per robot.
      if (IsValidRobotName(sample.robot_id()) || sample.robot_id() == "fleet") {
        event->tile.robot_id = RobotId{sample.robot_id()};
      }
      event->error = tile.status().WithContext(
          topic_name_ + ": tile (" + std::to_string(sample.tile_x()) + ", " +
          std::to_string(sample.tile_y()) + ") from " + sample.robot_id().substr(0, 64));
      return;
    }
    event->kind = TileEvent::Kind::kTile;
    event->tile = std::move(tile).value();
  }

  // Only a disposal means the tile is gone; a writer that vanished leaves its tiles in place.
  void OnInstanceGone(const dds::SampleInfo& info, TileEvent event) {
    if (info.instance_state != dds::NOT_ALIVE_DISPOSED_INSTANCE_STATE) return;
    std::lock_guard lock(mutex_);
    const auto it = key_by_instance_.find(info.instance_handle);
    if (it == key_by_instance_.end()) return;
    event.kind = TileEvent::Kind::kRemoved;
    event.tile.robot_id = it->second.first;
    event.tile.tile = it->second.second;
    Received received;
    received.event = std::move(event);
    Push(std::move(received));
  }

  // Queued by the participant that wrote it (its GUID prefix): Drain() serves participants in
  // turn, so one participant's flood does not delay another's tiles.
  void Push(Received received) {
    const std::string participant = received.event.writer.substr(0, 24);
    received_.Push(participant, std::move(received));
  }

  void Notify() {
    if (wake_up_) wake_up_->Notify();
  }

  const Participant& participant_;  // outlives the reader
  const std::string topic_name_;
  std::shared_ptr<WakeUp> wake_up_;
  const TileDecodeLimits limits_;
  FairSampleQueue<Received> received_;
  std::mutex mutex_;
  // get_key_value is not supported by Fast DDS 2.9: remember each instance's key.
  std::map<dds::InstanceHandle_t, std::pair<RobotId, TileId>> key_by_instance_;  // mutex_
};

StatusOr<std::unique_ptr<VectorTileReader>> VectorTileReader::Create(
    Participant& participant, const std::string& topic_name, std::shared_ptr<WakeUp> wake_up,
    const TileDecodeLimits& limits, const std::optional<TileRegionSelection>& region) {
  std::unique_ptr<VectorTileReader> self(new VectorTileReader());
  self->listener_ = std::make_unique<Listener>(participant, topic_name, std::move(wake_up), limits);
  const EndpointQos qos = topic_name == kFusedTilesTopic ? ServedStateQos() : VectorTileQos();
  std::optional<ContentFilter> filter;
  if (region) {
    filter = ContentFilter{kTileRegionFilterClass, kTileRegionFilterExpression,
                           region->ToParameters(), "a shard's tiles"};
  }
  FLEETMAP_ASSIGN_OR_RETURN(self->endpoint_,
                            ReaderEndpoint::Create(participant, topic_name, VectorTileTypeSupport(),
                                                   qos.reader, self->listener_.get(), filter));
  return self;
}

StatusOr<std::unique_ptr<VectorTileReader>> VectorTileReader::CreateForRobot(
    Participant& participant, const std::string& topic_name, const RobotId& robot,
    std::shared_ptr<WakeUp> wake_up, const TileDecodeLimits& limits) {
  std::unique_ptr<VectorTileReader> self(new VectorTileReader());
  self->listener_ = std::make_unique<Listener>(participant, topic_name, std::move(wake_up), limits);
  FLEETMAP_ASSIGN_OR_RETURN(self->endpoint_,
                            ReaderEndpoint::Create(participant, topic_name, VectorTileTypeSupport(),
                                                   VectorTileQos().reader, self->listener_.get(),
                                                   ContentFilter::OnlyRobot(robot.value)));
  return self;
}

VectorTileReader::~VectorTileReader() { endpoint_.reset(); }

std::vector<TileEvent> VectorTileReader::Drain(size_t max_events) {
  return listener_->Drain(max_events);
}

size_t VectorTileReader::DrainCount() { return listener_->DrainCount(); }

size_t VectorTileReader::queued() const { return listener_->queued(); }

size_t VectorTileReader::dropped() const { return listener_->dropped(); }

int VectorTileReader::matched_writers() const {
  dds::SubscriptionMatchedStatus matched;
  endpoint_->reader()->get_subscription_matched_status(matched);
  return matched.current_count;
}

}  // namespace fleetmap::transport

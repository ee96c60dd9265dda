#include "common/transport/vector_tile_reader.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <map>
#include <mutex>

#include "common/core/sample_queue.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"
#include "common/transport/internal/writer_id.hpp"
#include "fleetmap_msgs/msg/VectorTile.h"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;
using fleetmap_msgs::msg::dds_::VectorTile_;

// Runs on DDS threads: decodes and queues, nothing more.
class VectorTileReader::Listener : public dds::DataReaderListener, public MalformedSink {
 public:
  Listener(std::string topic_name, std::shared_ptr<WakeUp> wake_up, const TileDecodeLimits& limits)
      : topic_name_(std::move(topic_name)),
        wake_up_(std::move(wake_up)),
        limits_(limits),
        events_(1 << 16) {}

  void on_data_available(dds::DataReader* reader) override {
    TakeAll<VectorTile_>(reader, this,
                         [this](const VectorTile_& sample, const dds::SampleInfo& info) {
                           TileEvent event;
                           event.writer = WriterId(info.publication_handle);
                           event.received = Clock::now();
                           if (info.valid_data) {
                             OnSample(sample, info, std::move(event));
                           } else {
                             OnInstanceGone(info, std::move(event));
                           }
                         });
    Notify();
  }

  std::vector<TileEvent> Drain() { return events_.Drain(); }
  size_t dropped() const { return events_.dropped(); }

 protected:
  void OnMalformed(const Status& error) override {
    TileEvent event;
    event.kind = TileEvent::Kind::kRejected;
    event.error = error.WithContext(topic_name_ + ": malformed VectorTile payload");
    events_.Push(std::move(event));
  }

 private:
  void OnSample(const VectorTile_& sample, const dds::SampleInfo& info, TileEvent event) {
    StatusOr<VectorTileMessage> tile = FromIdl(sample, limits_);
    if (!tile.ok()) {
      event.kind = TileEvent::Kind::kRejected;
      // Name the robot when the name itself is sound, so the server can count per robot.
      if (IsValidRobotName(sample.robot_id()) || sample.robot_id() == "fleet") {
        event.tile.robot_id = RobotId{sample.robot_id()};
      }
      event.error = tile.status().WithContext(
          topic_name_ + ": tile (" + std::to_string(sample.tile_x()) + ", " +
          std::to_string(sample.tile_y()) + ") from " + sample.robot_id().substr(0, 64));
      events_.Push(std::move(event));
      return;
    }
    {
      std::lock_guard lock(mutex_);
      key_by_instance_[info.instance_handle] = {tile->robot_id, tile->tile};
    }
    event.kind = TileEvent::Kind::kTile;
    event.serialized_bytes = VectorTile_::getCdrSerializedSize(sample) + 4;
    event.tile = std::move(tile).value();
    events_.Push(std::move(event));
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
    events_.Push(std::move(event));
  }

  void Notify() {
    if (wake_up_) wake_up_->Notify();
  }

  const std::string topic_name_;
  std::shared_ptr<WakeUp> wake_up_;
  const TileDecodeLimits limits_;
  SampleQueue<TileEvent> events_;
  std::mutex mutex_;
  // get_key_value is not supported by Fast DDS 2.9: remember each instance's key.
  std::map<dds::InstanceHandle_t, std::pair<RobotId, TileId>> key_by_instance_;  // mutex_
};

StatusOr<std::unique_ptr<VectorTileReader>> VectorTileReader::Create(
    Participant& participant, const std::string& topic_name, std::shared_ptr<WakeUp> wake_up,
    const TileDecodeLimits& limits) {
  std::unique_ptr<VectorTileReader> self(new VectorTileReader());
  self->listener_ = std::make_unique<Listener>(topic_name, std::move(wake_up), limits);
  FLEETMAP_ASSIGN_OR_RETURN(self->endpoint_,
                            ReaderEndpoint::Create(participant, topic_name, VectorTileTypeSupport(),
                                                   VectorTileQos().reader, self->listener_.get()));
  return self;
}

VectorTileReader::~VectorTileReader() { endpoint_.reset(); }

std::vector<TileEvent> VectorTileReader::Drain() { return listener_->Drain(); }

size_t VectorTileReader::dropped() const { return listener_->dropped(); }

}  // namespace fleetmap::transport

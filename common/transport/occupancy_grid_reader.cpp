#include "common/transport/occupancy_grid_reader.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "common/core/sample_queue.hpp"
#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "nav_msgs/msg/OccupancyGrid.h"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;

class OccupancyGridReader::Listener : public dds::DataReaderListener, public MalformedSink {
 public:
  Listener(std::string topic_name, std::shared_ptr<WakeUp> wake_up)
      : topic_name_(std::move(topic_name)), wake_up_(std::move(wake_up)), maps_(8) {}

  void on_data_available(dds::DataReader* reader) override {
    TakeAll<nav_msgs::msg::dds_::OccupancyGrid_>(
        reader, this, [this](const auto& sample, const dds::SampleInfo& info) {
          if (!info.valid_data) return;
          StatusOr<MapMessage> message = FromIdl(sample);
          if (message.ok()) {
            message->serialized_bytes = PayloadBytes(sample);
            maps_.Push(std::move(message));
          } else {
            maps_.Push(message.status().WithContext(topic_name_));
          }
        });
    if (wake_up_) wake_up_->Notify();
  }

  std::vector<StatusOr<MapMessage>> Drain() { return maps_.Drain(); }

 protected:
  // A payload that failed its CDR shape check before decoding.
  void OnMalformed(const Status& error) override {
    maps_.Push(error.WithContext(topic_name_ + ": malformed OccupancyGrid payload"));
  }

 private:
  const std::string topic_name_;
  std::shared_ptr<WakeUp> wake_up_;
  SampleQueue<StatusOr<MapMessage>> maps_;  // a few: only the newest map matters
};

StatusOr<std::unique_ptr<OccupancyGridReader>> OccupancyGridReader::Create(
    Participant& participant, const std::string& topic_name, std::shared_ptr<WakeUp> wake_up) {
  std::unique_ptr<OccupancyGridReader> self(new OccupancyGridReader());
  self->listener_ = std::make_unique<Listener>(topic_name, std::move(wake_up));
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_, ReaderEndpoint::Create(participant, topic_name, OccupancyGridTypeSupport(),
                                              OccupancyGridQos().reader, self->listener_.get()));
  return self;
}

OccupancyGridReader::~OccupancyGridReader() { endpoint_.reset(); }

std::vector<StatusOr<MapMessage>> OccupancyGridReader::Drain() { return listener_->Drain(); }

const std::string& OccupancyGridReader::topic_name() const { return endpoint_->topic_name(); }

}  // namespace fleetmap::transport

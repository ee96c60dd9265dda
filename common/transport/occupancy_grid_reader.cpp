#include "common/transport/occupancy_grid_reader.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "common/transport/checked_type_support.hpp"
#include "common/transport/conversions.hpp"
#include "common/transport/endpoint.hpp"
#include "common/transport/idl_shapes.hpp"
#include "common/transport/qos.hpp"
#include "nav_msgs/msg/OccupancyGridPubSubTypes.h"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;
using nav_msgs::msg::dds_::OccupancyGrid_PubSubType;

class OccupancyGridReader::Listener : public dds::DataReaderListener {
 public:
  Listener(std::string topic_name, std::shared_ptr<WakeUp> wake_up)
      : topic_name_(std::move(topic_name)), wake_up_(std::move(wake_up)), maps_(8) {}

  void on_data_available(dds::DataReader* reader) override {
    nav_msgs::msg::dds_::OccupancyGrid_ sample;
    dds::SampleInfo info;
    while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      StatusOr<MapMessage> message = FromIdl(sample);
      if (message.ok()) {
        message->serialized_bytes =
            nav_msgs::msg::dds_::OccupancyGrid_::getCdrSerializedSize(sample);
        maps_.Push(std::move(message));
      } else {
        maps_.Push(message.status().WithContext(topic_name_));
      }
    }
    if (wake_up_) wake_up_->Notify();
  }

  std::vector<StatusOr<MapMessage>> Drain() { return maps_.Drain(); }

  // A payload that failed its CDR shape check before decoding.
  void OnMalformed(const Status& error) {
    maps_.Push(error.WithContext(topic_name_ + ": malformed OccupancyGrid payload"));
    if (wake_up_) wake_up_->Notify();
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
      self->endpoint_,
      ReaderEndpoint::Create(
          participant, topic_name,
          dds::TypeSupport(new CheckedPubSubType<OccupancyGrid_PubSubType>(
              OccupancyGridShape(), [listener = self->listener_.get()](
                                        const Status& error) { listener->OnMalformed(error); })),
          OccupancyGridQos().reader, self->listener_.get()));
  return self;
}

OccupancyGridReader::~OccupancyGridReader() { endpoint_.reset(); }

std::vector<StatusOr<MapMessage>> OccupancyGridReader::Drain() { return listener_->Drain(); }

const std::string& OccupancyGridReader::topic_name() const { return endpoint_->topic_name(); }

}  // namespace fleetmap::transport

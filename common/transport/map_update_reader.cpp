#include "common/transport/map_update_reader.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include "common/core/sample_queue.hpp"
#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;
using map_msgs::msg::dds_::OccupancyGridUpdate_;

class MapUpdateReader::Listener : public dds::DataReaderListener, public MalformedSink {
 public:
  Listener(std::string topic_name, std::shared_ptr<WakeUp> wake_up)
      : topic_name_(std::move(topic_name)), wake_up_(std::move(wake_up)), updates_(1024) {}

  void on_data_available(dds::DataReader* reader) override {
    TakeAll<OccupancyGridUpdate_>(
        reader, this, [this](const OccupancyGridUpdate_& sample, const dds::SampleInfo& info) {
          if (!info.valid_data) return;
          StatusOr<MapUpdate> update = FromIdl(sample);
          if (update.ok()) update->serialized_bytes = PayloadBytes(sample);
          updates_.Push(update.ok()
                            ? std::move(update)
                            : StatusOr<MapUpdate>(update.status().WithContext(topic_name_)));
        });
    if (wake_up_) wake_up_->Notify();
  }

  std::vector<StatusOr<MapUpdate>> Drain() { return updates_.Drain(); }

 protected:
  void OnMalformed(const Status& error) override {
    updates_.Push(error.WithContext(topic_name_ + ": malformed OccupancyGridUpdate payload"));
  }

 private:
  const std::string topic_name_;
  std::shared_ptr<WakeUp> wake_up_;
  SampleQueue<StatusOr<MapUpdate>> updates_;
};

StatusOr<std::unique_ptr<MapUpdateReader>> MapUpdateReader::Create(
    Participant& participant, const std::string& topic_name, std::shared_ptr<WakeUp> wake_up) {
  std::unique_ptr<MapUpdateReader> self(new MapUpdateReader());
  self->listener_ = std::make_unique<Listener>(topic_name, std::move(wake_up));
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      ReaderEndpoint::Create(participant, topic_name, OccupancyGridUpdateTypeSupport(),
                             OccupancyGridUpdateQos().reader, self->listener_.get()));
  return self;
}

MapUpdateReader::~MapUpdateReader() { endpoint_.reset(); }

std::vector<StatusOr<MapUpdate>> MapUpdateReader::Drain() { return listener_->Drain(); }

}  // namespace fleetmap::transport

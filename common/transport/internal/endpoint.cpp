#include "common/transport/internal/endpoint.hpp"

#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;

StatusOr<std::unique_ptr<WriterEndpoint>> WriterEndpoint::Create(Participant& participant,
                                                                 const std::string& topic_name,
                                                                 dds::TypeSupport type,
                                                                 const dds::DataWriterQos& qos) {
  std::unique_ptr<WriterEndpoint> self(new WriterEndpoint(participant, topic_name));
  FLEETMAP_ASSIGN_OR_RETURN(self->topic_, participant.AcquireTopic(topic_name, type));
  self->writer_ = participant.publisher()->create_datawriter(self->topic_, qos);
  if (self->writer_ == nullptr) {
    return UnavailableError("could not create a DDS writer on " + topic_name);
  }
  return self;
}

WriterEndpoint::~WriterEndpoint() {
  if (writer_ != nullptr) participant_.publisher()->delete_datawriter(writer_);
  if (topic_ != nullptr) participant_.ReleaseTopic(topic_);
}

StatusOr<std::unique_ptr<ReaderEndpoint>> ReaderEndpoint::Create(
    Participant& participant, const std::string& topic_name, dds::TypeSupport type,
    const dds::DataReaderQos& qos, dds::DataReaderListener* listener) {
  std::unique_ptr<ReaderEndpoint> self(new ReaderEndpoint(participant, topic_name));
  FLEETMAP_ASSIGN_OR_RETURN(self->topic_, participant.AcquireTopic(topic_name, type));
  self->reader_ = participant.subscriber()->create_datareader(self->topic_, qos, listener,
                                                              dds::StatusMask::all());
  if (self->reader_ == nullptr) {
    return UnavailableError("could not create a DDS reader on " + topic_name);
  }
  return self;
}

ReaderEndpoint::~ReaderEndpoint() {
  if (reader_ != nullptr) {
    reader_->set_listener(nullptr);
    participant_.subscriber()->delete_datareader(reader_);
  }
  if (topic_ != nullptr) participant_.ReleaseTopic(topic_);
}

}  // namespace fleetmap::transport

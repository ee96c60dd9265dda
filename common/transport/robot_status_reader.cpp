#include "common/transport/robot_status_reader.hpp"

#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <map>
#include <mutex>
#include <set>

#include "common/core/sample_queue.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "common/transport/internal/writer_id.hpp"
#include "common/transport/topics.hpp"
#include "fleetmap_msgs/msg/RobotStatus.h"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;

const char* RobotEventKindName(RobotEvent::Kind kind) {
  switch (kind) {
    case RobotEvent::Kind::kStatus:
      return "status";
    case RobotEvent::Kind::kLeft:
      return "left";
    case RobotEvent::Kind::kLost:
      return "lost";
    case RobotEvent::Kind::kRejected:
      return "rejected";
  }
  return "unknown";
}

RobotEvent RobotEvent::Alive(RobotStatus status) {
  RobotEvent event;
  event.kind = Kind::kStatus;
  event.robot = status.robot;
  event.status = std::move(status);
  return event;
}

RobotEvent RobotEvent::Gone(Kind kind, RobotId robot, std::string writer) {
  RobotEvent event;
  event.kind = kind;
  event.robot = std::move(robot);
  event.writer = std::move(writer);
  return event;
}

RobotEvent RobotEvent::Rejected(Status error) {
  RobotEvent event;
  event.kind = Kind::kRejected;
  event.error = std::move(error);
  return event;
}

// Runs on DDS threads: turns samples and liveliness changes into RobotEvents, nothing more.
class RobotStatusReader::Listener : public dds::DataReaderListener, public MalformedSink {
 public:
  explicit Listener(std::shared_ptr<WakeUp> wake_up) : wake_up_(std::move(wake_up)) {}

  void on_data_available(dds::DataReader* reader) override {
    TakeAll<fleetmap_msgs::msg::dds_::RobotStatus_>(
        reader, this, [this](const auto& sample, const dds::SampleInfo& info) {
          if (info.valid_data) {
            OnSample(sample, info);
          } else {
            OnInstanceGone(info);
          }
        });
    Notify();
  }

  // A writer whose lease lapsed: its process died, hung or was cut off.
  void on_liveliness_changed(dds::DataReader* /*reader*/,
                             const dds::LivelinessChangedStatus& status) override {
    GuardListener(this, "a liveliness change", [&] {
      if (status.not_alive_count_change > 0) WriterGone(status.last_publication_handle);
    });
  }

  // A writer that went away without disposing its robots (a clean exit that skipped Leave()).
  // After a Leave() the robot is already gone and the node ignores the repeat.
  void on_subscription_matched(dds::DataReader* /*reader*/,
                               const dds::SubscriptionMatchedStatus& status) override {
    GuardListener(this, "a writer leaving", [&] {
      if (status.current_count_change < 0) WriterGone(status.last_publication_handle);
    });
  }

  std::vector<RobotEvent> Drain() { return events_.Drain(); }

 protected:
  // A payload that failed its CDR shape check before decoding.
  void OnMalformed(const Status& error) override {
    events_.Push(RobotEvent::Rejected(error.WithContext("malformed RobotStatus payload")));
  }

 private:
  void OnSample(const fleetmap_msgs::msg::dds_::RobotStatus_& sample, const dds::SampleInfo& info) {
    StatusOr<RobotStatus> status = FromIdl(sample);
    if (!status.ok()) {
      events_.Push(RobotEvent::Rejected(status.status()));
      return;
    }
    {
      std::lock_guard lock(mutex_);
      robots_by_writer_[info.publication_handle].insert(status->robot);
      robot_by_instance_[info.instance_handle] = status->robot;
    }
    RobotEvent event = RobotEvent::Alive(*std::move(status));
    event.writer = WriterId(info.publication_handle);
    events_.Push(std::move(event));
  }

  void OnInstanceGone(const dds::SampleInfo& info) {
    // get_key_value is not supported by Fast DDS 2.9: name the robot from its earlier samples.
    RobotId robot;
    {
      std::lock_guard lock(mutex_);
      const auto it = robot_by_instance_.find(info.instance_handle);
      if (it == robot_by_instance_.end()) return;
      robot = it->second;
    }
    const bool disposed = info.instance_state == dds::NOT_ALIVE_DISPOSED_INSTANCE_STATE;
    events_.Push(RobotEvent::Gone(disposed ? RobotEvent::Kind::kLeft : RobotEvent::Kind::kLost,
                                  std::move(robot), WriterId(info.publication_handle)));
  }

  void WriterGone(const dds::InstanceHandle_t& writer) {
    {
      std::lock_guard lock(mutex_);
      const auto it = robots_by_writer_.find(writer);
      if (it == robots_by_writer_.end()) return;
      for (const RobotId& robot : it->second) {
        events_.Push(RobotEvent::Gone(RobotEvent::Kind::kLost, robot, WriterId(writer)));
      }
      robots_by_writer_.erase(it);
    }
    Notify();
  }

  void Notify() {
    if (wake_up_) wake_up_->Notify();
  }

  std::shared_ptr<WakeUp> wake_up_;
  SampleQueue<RobotEvent> events_;
  std::mutex mutex_;
  // Which robots each writer speaks for, to name them when its liveliness lapses.
  std::map<dds::InstanceHandle_t, std::set<RobotId>> robots_by_writer_;  // guarded by mutex_
  std::map<dds::InstanceHandle_t, RobotId> robot_by_instance_;           // guarded by mutex_
};

StatusOr<std::unique_ptr<RobotStatusReader>> RobotStatusReader::Create(
    Participant& participant, std::shared_ptr<WakeUp> wake_up) {
  std::unique_ptr<RobotStatusReader> self(new RobotStatusReader());
  self->listener_ = std::make_unique<Listener>(std::move(wake_up));
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      ReaderEndpoint::Create(participant, kRobotStatusTopic, RobotStatusTypeSupport(),
                             RobotStatusQos().reader, self->listener_.get()));
  return self;
}

StatusOr<std::unique_ptr<RobotStatusReader>> RobotStatusReader::CreateForRobot(
    Participant& participant, const RobotId& robot, std::shared_ptr<WakeUp> wake_up) {
  std::unique_ptr<RobotStatusReader> self(new RobotStatusReader());
  self->listener_ = std::make_unique<Listener>(std::move(wake_up));
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      ReaderEndpoint::Create(participant, kRobotStatusTopic, RobotStatusTypeSupport(),
                             RobotStatusQos().reader, self->listener_.get(),
                             ContentFilter::OnlyRobot(robot.value)));
  return self;
}

RobotStatusReader::~RobotStatusReader() { endpoint_.reset(); }

std::vector<RobotEvent> RobotStatusReader::Drain() { return listener_->Drain(); }

}  // namespace fleetmap::transport

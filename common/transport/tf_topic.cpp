#include "common/transport/tf_topic.hpp"

#include <atomic>
#include <cmath>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "common/core/sample_queue.hpp"
#include "common/transport/internal/cdr_codec.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "common/transport/topics.hpp"
#include "tf2_msgs/msg/TFMessage.h"

namespace fleetmap::transport {
namespace {

namespace dds = eprosima::fastdds::dds;
using geometry_msgs::msg::dds_::TransformStamped_;

TransformStamped_ TransformToIdl(const FrameTransform& transform) {
  TransformStamped_ out;
  out.header().stamp(ToIdl(transform.stamp));
  out.header().frame_id(transform.parent);
  out.child_frame_id(transform.child);
  const geometry_msgs::msg::dds_::Pose_ pose = ToIdl3D(transform.parent_from_child);
  out.transform().translation().x(pose.position().x());
  out.transform().translation().y(pose.position().y());
  out.transform().translation().z(0.0);
  out.transform().rotation(pose.orientation());
  return out;
}

StatusOr<FrameTransform> TransformFromIdl(const TransformStamped_& sample) {
  geometry_msgs::msg::dds_::Pose_ pose;
  pose.position().x(sample.transform().translation().x());
  pose.position().y(sample.transform().translation().y());
  pose.orientation(sample.transform().rotation());
  if (!(std::abs(sample.transform().translation().z()) <= 1e-3)) {
    return InvalidArgumentError("rt/tf: " + sample.header().frame_id().substr(0, 64) + " -> " +
                                sample.child_frame_id().substr(0, 64) + " is not planar (z)");
  }
  StatusOr<Pose2> planar = FromIdl(pose);
  if (!planar.ok()) {
    return planar.status().WithContext("rt/tf: " + sample.header().frame_id().substr(0, 64) +
                                       " -> " + sample.child_frame_id().substr(0, 64));
  }
  return FrameTransform{FromIdl(sample.header().stamp()), sample.header().frame_id(),
                        sample.child_frame_id(), *planar};
}

}  // namespace

std::string RobotMapFrame(const std::string& robot) { return robot + "/map"; }

StatusOr<std::unique_ptr<TfWriter>> TfWriter::Create(Participant& participant) {
  std::unique_ptr<TfWriter> self(new TfWriter());
  FLEETMAP_ASSIGN_OR_RETURN(
      self->endpoint_,
      WriterEndpoint::Create(participant, kTfTopic, TfMessageTypeSupport(), TfQos().writer));
  return self;
}

TfWriter::~TfWriter() = default;

StatusOr<size_t> TfWriter::Write(const std::vector<FrameTransform>& transforms) {
  tf2_msgs::msg::dds_::TFMessage_ sample;
  for (const FrameTransform& transform : transforms) {
    if (transform.parent.empty() || transform.child.empty()) {
      return InvalidArgumentError("a transform needs a parent and a child frame");
    }
    if (!transform.parent_from_child.finite()) {
      return InvalidArgumentError("the transform " + transform.parent + " -> " + transform.child +
                                  " is not finite");
    }
    sample.transforms().push_back(TransformToIdl(transform));
  }
  if (!endpoint_->writer()->write(&sample)) {
    return UnavailableError("could not write on " + endpoint_->topic_name());
  }
  return PayloadBytes(sample);
}

// Runs on DDS threads: checks, decodes and queues.
class TfReader::Listener : public dds::DataReaderListener, public MalformedSink {
 public:
  explicit Listener(std::shared_ptr<WakeUp> wake_up) : wake_up_(std::move(wake_up)) {}

  void on_data_available(dds::DataReader* reader) override {
    TakeAll<tf2_msgs::msg::dds_::TFMessage_>(
        reader, this, [this](const tf2_msgs::msg::dds_::TFMessage_& sample, const auto& info) {
          if (!info.valid_data) return;
          for (const TransformStamped_& stamped : sample.transforms()) {
            StatusOr<FrameTransform> transform = TransformFromIdl(stamped);
            if (transform.ok()) {
              transforms_.Push(*std::move(transform));
            } else {
              ++refused_;
            }
          }
        });
    if (wake_up_) wake_up_->Notify();
  }

  std::vector<FrameTransform> Drain() { return transforms_.Drain(); }
  uint64_t refused_transforms() const { return refused_.load() + refused(); }

 protected:
  void OnMalformed(const Status&) override {}

 private:
  std::shared_ptr<WakeUp> wake_up_;
  SampleQueue<FrameTransform> transforms_;
  std::atomic<uint64_t> refused_{0};
};

StatusOr<std::unique_ptr<TfReader>> TfReader::Create(Participant& participant,
                                                     std::shared_ptr<WakeUp> wake_up) {
  std::unique_ptr<TfReader> self(new TfReader());
  self->listener_ = std::make_unique<Listener>(std::move(wake_up));
  FLEETMAP_ASSIGN_OR_RETURN(self->endpoint_,
                            ReaderEndpoint::Create(participant, kTfTopic, TfMessageTypeSupport(),
                                                   TfQos().reader, self->listener_.get()));
  return self;
}

TfReader::~TfReader() { endpoint_.reset(); }

std::vector<FrameTransform> TfReader::Drain() { return listener_->Drain(); }

uint64_t TfReader::refused() const { return listener_->refused_transforms(); }

}  // namespace fleetmap::transport

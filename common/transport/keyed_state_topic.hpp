#pragma once

// Readers and writers of the keyed state topics that carry one instance per thing: the entities
// agents recognise (rt/fleetmap/entities), the sub-map graph (rt/fleetmap/submap_graph) and the
// learned object models (rt/fleetmap/object_templates, rt/fleetmap/objects), the route graph
// (rt/fleetmap/route_graph), the robots' map
// frames (rt/fleetmap/robot_frames), operators' admissions (rt/fleetmap/admissions) and the
// servers (rt/fleetmap/servers). All share one QoS (KeyedStateQos: reliable, transient local, keep
// last 1 per instance), with exclusive ownership on those a server serves (served_state.hpp), and
// one behaviour, so they are one template, instantiated in keyed_state_topic.cpp per message type.

#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/state_messages.hpp"

namespace fleetmap::transport {

class ReaderEndpoint;
class WriterEndpoint;

// A received instance, its disposal, or a refused sample.
template <typename Message>
struct KeyedEvent {
  enum class Kind { kSample, kRemoved, kRejected };
  Kind kind = Kind::kSample;
  Message message;     // kSample: the whole message; kRemoved: its key fields only
  Status error;        // kRejected: what was wrong, naming the topic and the sender if known
  std::string writer;  // the DDS writer that sent it
};

// Publishes instances of one keyed state topic. Call from one thread.
template <typename Message>
class KeyedStateWriter {
 public:
  static StatusOr<std::unique_ptr<KeyedStateWriter>> Create(Participant& participant);
  ~KeyedStateWriter();

  // Publishes the message as the current state of its instance; returns the serialized bytes.
  // Fails (kInvalidArgument) for a message that cannot go on the wire.
  StatusOr<size_t> Write(const Message& message);
  // Withdraws the instance `key` names (only its key fields are read).
  Status Dispose(const Message& key);
  int matched_readers() const;

 private:
  KeyedStateWriter() = default;
  std::unique_ptr<WriterEndpoint> endpoint_;
};

// Receives one keyed state topic. The DDS listener checks the CDR shape, decodes, validates and
// queues; Drain() hands the events over and may be called from one thread.
template <typename Message>
class KeyedStateReader {
 public:
  static StatusOr<std::unique_ptr<KeyedStateReader>> Create(
      Participant& participant, std::shared_ptr<WakeUp> wake_up = nullptr);
  // A reader of one robot's instance only, for the topics keyed by a robot id first (robot
  // frames; others fail with kInternal): the writers send it no other robot's (a content filter).
  static StatusOr<std::unique_ptr<KeyedStateReader>> CreateForRobot(
      Participant& participant, const RobotId& robot, std::shared_ptr<WakeUp> wake_up = nullptr);
  ~KeyedStateReader();

  std::vector<KeyedEvent<Message>> Drain();
  // Events dropped because the queue was full (the owner drained too slowly), since creation.
  size_t dropped() const;

 private:
  class Listener;
  KeyedStateReader() = default;

  std::unique_ptr<Listener> listener_;
  std::unique_ptr<ReaderEndpoint> endpoint_;
};

using EntityEvent = KeyedEvent<EntityMessage>;
using EntityWriter = KeyedStateWriter<EntityMessage>;
using EntityReader = KeyedStateReader<EntityMessage>;
using SubmapEvent = KeyedEvent<SubmapMessage>;
using SubmapWriter = KeyedStateWriter<SubmapMessage>;
using SubmapReader = KeyedStateReader<SubmapMessage>;
using ObjectTemplateEvent = KeyedEvent<ObjectTemplateMessage>;
using ObjectTemplateWriter = KeyedStateWriter<ObjectTemplateMessage>;
using ObjectTemplateReader = KeyedStateReader<ObjectTemplateMessage>;
using ObjectModelEvent = KeyedEvent<ObjectModelMessage>;
using ObjectModelWriter = KeyedStateWriter<ObjectModelMessage>;
using ObjectModelReader = KeyedStateReader<ObjectModelMessage>;
using RouteGraphEvent = KeyedEvent<RouteGraphMessage>;
using RouteGraphWriter = KeyedStateWriter<RouteGraphMessage>;
using RouteGraphReader = KeyedStateReader<RouteGraphMessage>;
using RobotFrameEvent = KeyedEvent<RobotFrameMessage>;
using RobotFrameWriter = KeyedStateWriter<RobotFrameMessage>;
using RobotFrameReader = KeyedStateReader<RobotFrameMessage>;
using RobotAdmissionEvent = KeyedEvent<RobotAdmissionMessage>;
using RobotAdmissionWriter = KeyedStateWriter<RobotAdmissionMessage>;
using RobotAdmissionReader = KeyedStateReader<RobotAdmissionMessage>;
using FleetServerEvent = KeyedEvent<FleetServerMessage>;
using FleetServerWriter = KeyedStateWriter<FleetServerMessage>;
using FleetServerReader = KeyedStateReader<FleetServerMessage>;

}  // namespace fleetmap::transport

#include "common/transport/participant.hpp"

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/common/PortParameters.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <cstdlib>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <string>

#include "common/transport/internal/participant_identities.hpp"
#include "common/transport/internal/robot_id_filter.hpp"
#include "common/transport/internal/served_writers.hpp"
#include "common/transport/internal/tile_region_filter.hpp"
#include "common/transport/internal/writer_id.hpp"

namespace fleetmap::transport {
namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

constexpr int kMaxDomainId = 232;  // the highest domain whose RTPS ports fit in 16 bits

// Every writer of a participant's peers sends to one UDP port of it: on the server, every robot's
// tiles, and a flood's, share one socket. Linux's default 208 KB receive buffer holds three 64 KB
// fragments, and past it the kernel drops what arrives, an honest robot's tile as readily as a
// flood's, to be repaired a heartbeat later (measured: about 20 000 drops in one 15 s flood of
// `bench fleet --hostile`, honest p99 0.9-2.1 s). The kernel caps the request at
// net.core.rmem_max / wmem_max (docs/fleet.md, "Socket buffers").
constexpr uint32_t kSocketBufferBytes = 4u << 20;

// Localhost-only discovery announces to the metatraffic port of participant ids 0..N-1 on
// 127.0.0.1, port = 7400 + 250 domain + 10 + 2 id. 128 ids (what we had) reached 7664 + 250 domain:
// the discovery ports of domain + 1 (its multicast port is id 120's, its participant 0 listens on
// id 125's), so fleets on adjacent domains found each other and fused. Only the ids whose
// metatraffic and user ports stay below the next domain's range are announced to: 120 participants
// per domain and host (DomainIsolationTest).
uint32_t LocalhostParticipantsPerDomain() {
  const eprosima::fastrtps::rtps::PortParameters ports;
  return (ports.domainIDGain - ports.offsetd1) / ports.participantIDGain;
}

bool EnvironmentFlag(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && std::string(value) == "1";
}

eprosima::fastrtps::Duration_t ToDuration(std::chrono::milliseconds ms) {
  return eprosima::fastrtps::Duration_t(static_cast<double>(ms.count()) / 1000.0);
}

// The discovery servers of `list` (ROS_DISCOVERY_SERVER syntax), or nullopt if it is not one.
std::optional<eprosima::fastdds::rtps::RemoteServerList_t> DiscoveryServers(
    const std::string& list) {
  eprosima::fastdds::rtps::RemoteServerList_t servers;
  if (!eprosima::fastdds::rtps::load_environment_server_info(list, servers) || servers.empty()) {
    return std::nullopt;
  }
  return servers;
}

dds::DomainParticipantQos MakeQos(const ParticipantOptions& options, bool localhost_only,
                                  const std::string& discovery_server) {
  dds::DomainParticipantQos qos;
  qos.name(options.name);
  qos.transport().listen_socket_buffer_size = kSocketBufferBytes;
  qos.transport().send_socket_buffer_size = kSocketBufferBytes;
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.leaseDuration = ToDuration(options.participant_lease);
  discovery.leaseDuration_announcementperiod = ToDuration(options.participant_lease / 4);
  if (!discovery_server.empty()) {
    // A client of the discovery servers: it announces itself to them only, and learns from them
    // only the participants it has endpoints to match (ResolveDiscoveryServer checked the list).
    discovery.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
    discovery.m_DiscoveryServers = *DiscoveryServers(discovery_server);
  }
  if (localhost_only) {
    // UDP on loopback only, unicast discovery through initial peers: no packet leaves the host,
    // and no multicast is needed (the loopback interface has none).
    auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
    udp->interfaceWhiteList.emplace_back("127.0.0.1");
    udp->maxInitialPeersRange = LocalhostParticipantsPerDomain();
    udp->receiveBufferSize = kSocketBufferBytes;
    udp->sendBufferSize = kSocketBufferBytes;
    qos.transport().use_builtin_transports = false;
    qos.transport().user_transports.push_back(udp);

    Locator_t peer;
    peer.kind = LOCATOR_KIND_UDPv4;
    IPLocator::setIPv4(peer, 127, 0, 0, 1);
    qos.wire_protocol().builtin.initialPeersList.push_back(peer);

    Locator_t unicast;
    unicast.kind = LOCATOR_KIND_UDPv4;
    IPLocator::setIPv4(unicast, 127, 0, 0, 1);
    qos.wire_protocol().builtin.metatrafficUnicastLocatorList.push_back(unicast);
    qos.wire_protocol().default_unicast_locator_list.push_back(unicast);
  }
  return qos;
}

// The DDS Security plugins (PKI-DH, Access-Permissions, AES-GCM-GMAC) on `identity`'s files.
void AddSecurityProperties(const security::SecurityIdentity& identity,
                           dds::DomainParticipantQos* qos) {
  auto& properties = qos->properties().properties();
  const auto add = [&](const std::string& name, const std::string& value) {
    properties.emplace_back(name, value);
  };
  // Fast DDS reads "file://" + an absolute path (LoadIdentity gives absolute paths).
  const auto file = [](const std::string& path) { return "file://" + path; };
  add("dds.sec.auth.plugin", "builtin.PKI-DH");
  add("dds.sec.auth.builtin.PKI-DH.identity_ca", file(identity.ca_cert));
  add("dds.sec.auth.builtin.PKI-DH.identity_certificate", file(identity.cert));
  add("dds.sec.auth.builtin.PKI-DH.private_key", file(identity.key));
  add("dds.sec.auth.builtin.PKI-DH.identity_crl", file(identity.crl));
  add("dds.sec.access.plugin", "builtin.Access-Permissions");
  add("dds.sec.access.builtin.Access-Permissions.permissions_ca", file(identity.ca_cert));
  add("dds.sec.access.builtin.Access-Permissions.governance", file(identity.governance));
  add("dds.sec.access.builtin.Access-Permissions.permissions", file(identity.permissions));
  add("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace

StatusOr<int> ResolveDomainId(const std::optional<int>& requested) {
  int domain = 0;
  std::string source = "the default";
  if (requested.has_value()) {
    domain = *requested;
    source = "the domain option";
  } else if (const char* env = std::getenv("FLEETMAP_DOMAIN"); env != nullptr && *env != '\0') {
    char* end = nullptr;
    const long value = std::strtol(env, &end, 10);
    if (*end != '\0') {
      return InvalidArgumentError("FLEETMAP_DOMAIN=\"" + std::string(env) + "\" is not an integer");
    }
    domain = static_cast<int>(value);
    source = "FLEETMAP_DOMAIN";
  }
  if (domain < 0 || domain > kMaxDomainId) {
    return InvalidArgumentError("DDS domain " + std::to_string(domain) + " from " + source +
                                " is outside 0.." + std::to_string(kMaxDomainId));
  }
  return domain;
}

bool ResolveLocalhostOnly(const std::optional<bool>& requested) {
  if (requested.has_value()) return *requested;
  return EnvironmentFlag("FLEETMAP_LOCALHOST_ONLY") || EnvironmentFlag("ROS_LOCALHOST_ONLY");
}

StatusOr<std::string> ResolveDiscoveryServer(const std::optional<std::string>& requested) {
  std::string list;
  std::string source = "--discovery-server";
  if (requested.has_value()) {
    list = *requested;
  } else if (const char* env = std::getenv("ROS_DISCOVERY_SERVER"); env != nullptr) {
    list = env;
    source = "ROS_DISCOVERY_SERVER";
  }
  if (!list.empty() && !DiscoveryServers(list)) {
    return InvalidArgumentError(source + " \"" + list +
                                "\" is not a list of discovery servers (IP:PORT[;IP:PORT...])");
  }
  return list;
}

StatusOr<std::unique_ptr<Participant>> Participant::Create(const ParticipantOptions& options) {
  FLEETMAP_ASSIGN_OR_RETURN(const int domain_id, ResolveDomainId(options.domain_id));

  eprosima::fastrtps::LibrarySettingsAttributes library;
  library.intraprocess_delivery = options.intraprocess_delivery
                                      ? eprosima::fastrtps::INTRAPROCESS_FULL
                                      : eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(library);

  std::unique_ptr<Participant> self(new Participant());
  self->domain_id_ = domain_id;
  self->localhost_only_ = ResolveLocalhostOnly(options.localhost_only);
  FLEETMAP_ASSIGN_OR_RETURN(self->discovery_server_,
                            ResolveDiscoveryServer(options.discovery_server));

  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipantQos qos = MakeQos(options, self->localhost_only_, self->discovery_server_);
  dds::PublisherQos publisher_qos = dds::PUBLISHER_QOS_DEFAULT;
  dds::SubscriberQos subscriber_qos = dds::SUBSCRIBER_QOS_DEFAULT;
  self->identities_ = std::make_unique<ParticipantIdentities>();
  self->served_writers_ = std::make_unique<ServedWriters>();
  self->ownership_strength_ = options.ownership_strength;
  self->participant_lease_ = options.participant_lease;
  if (options.security) {
    AddSecurityProperties(*options.security, &qos);
    self->secured_ = true;
    // A robot's permissions let it publish only in the partition named after it, so a robot
    // cannot write as another at the DDS level; "" and "*" together read the default partition
    // (the server's topics) and every named one.
    if (options.security->role == security::Role::kRobot) {
      publisher_qos.partition().push_back(options.security->name.c_str());
    }
    subscriber_qos.partition().push_back("");
    subscriber_qos.partition().push_back("*");
  }
  self->participant_ =
      factory->create_participant(domain_id, qos, self->identities_.get(), dds::StatusMask::none());
  if (self->participant_ == nullptr) {
    if (options.security) {
      return UnavailableError("could not create a secured DDS participant on domain " +
                              std::to_string(domain_id) + " as " + options.security->name +
                              " (Fast DDS's log above says why)");
    }
    return UnavailableError("could not create a DDS participant on domain " +
                            std::to_string(domain_id));
  }
  // The robot-id filter of agents' readers, evaluated by the writers of this participant too.
  if (self->participant_->register_content_filter_factory(
          kRobotIdFilterClass, &RobotIdFilterFactory()) != ReturnCode_t::RETCODE_OK) {
    return UnavailableError("could not register the robot id content filter");
  }
  // The tile-region filter of shards' readers (docs/shards.md), evaluated here too.
  if (self->participant_->register_content_filter_factory(
          kTileRegionFilterClass, &TileRegionFilterFactory()) != ReturnCode_t::RETCODE_OK) {
    return UnavailableError("could not register the tile region content filter");
  }
  self->publisher_ = self->participant_->create_publisher(publisher_qos);
  self->subscriber_ = self->participant_->create_subscriber(subscriber_qos);
  if (self->publisher_ == nullptr || self->subscriber_ == nullptr) {
    return UnavailableError("could not create a DDS publisher/subscriber on domain " +
                            std::to_string(domain_id));
  }
  return self;
}

Participant::Participant() = default;

std::optional<std::string> Participant::AuthenticatedName(const std::string& writer_id) const {
  if (!secured_) return std::nullopt;
  return identities_->NameOf(writer_id);
}

std::optional<std::string> Participant::HostOf(const std::string& writer_id) const {
  return identities_->HostOf(writer_id);
}

size_t Participant::RemoteWritersOf(const std::string& topic_name) const {
  return identities_->RemoteWritersOf(topic_name);
}

std::optional<double> Participant::SecondsToAuthenticate(const std::string& name) const {
  if (!secured_) return std::nullopt;
  return identities_->SecondsUntilAuthenticated(name);
}

std::string Participant::id() const {
  eprosima::fastrtps::rtps::InstanceHandle_t handle;
  const auto& prefix = participant_->guid().guidPrefix.value;
  for (size_t i = 0; i < sizeof(prefix); ++i) handle.value[i] = prefix[i];
  return WriterId(handle).substr(0, 24);
}

size_t Participant::RepublishServedState() { return served_writers_->WriteAgain(); }

Participant::~Participant() {
  if (participant_ == nullptr) return;
  // Readers and writers are gone by contract; this also removes any topic still held.
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

StatusOr<dds::Topic*> Participant::AcquireTopic(const std::string& name, dds::TypeSupport type) {
  auto it = topics_.find(name);
  if (it != topics_.end()) {
    if (it->second.topic->get_type_name() != type.get_type_name()) {
      return InvalidArgumentError("topic " + name + " already has type " +
                                  it->second.topic->get_type_name() + ", not " +
                                  type.get_type_name());
    }
    ++it->second.users;
    return it->second.topic;
  }
  if (participant_->find_type(type.get_type_name()).empty()) {
    if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
      return UnavailableError("could not register DDS type " + type.get_type_name());
    }
  }
  dds::Topic* topic =
      participant_->create_topic(name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) return UnavailableError("could not create DDS topic " + name);
  topics_[name] = TopicEntry{topic, 1};
  return topic;
}

void Participant::ReleaseTopic(dds::Topic* topic) {
  for (auto it = topics_.begin(); it != topics_.end(); ++it) {
    if (it->second.topic != topic) continue;
    if (--it->second.users == 0) {
      participant_->delete_topic(topic);
      topics_.erase(it);
    }
    return;
  }
}

Status ParticipantOptions::UseSecurityFolder(const std::string& dir, const std::string& identity) {
  FLEETMAP_ASSIGN_OR_RETURN(security, security::LoadIdentity(dir, identity));
  return Status::Ok();
}

void ParticipantOptions::Describe(OptionsPrinter& out) const {
  out.Add("domain_id", domain_id);
  out.Add("name", name);
  out.Add("localhost_only", localhost_only);
  out.Add("intraprocess_delivery", intraprocess_delivery);
  out.Add("participant_lease", participant_lease);
  out.Add("ownership_strength", ownership_strength);
  out.Add("discovery_server", discovery_server.value_or("(ROS_DISCOVERY_SERVER, else simple)"));
  out.Add("security", security ? security->name + " (" + security::RoleName(security->role) + ", " +
                                     security->cert + ")"
                               : std::string("off"));
}

}  // namespace fleetmap::transport

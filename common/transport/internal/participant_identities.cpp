#include "common/transport/internal/participant_identities.hpp"

#include <fastdds/rtps/common/Locator.h>
#include <fastdds/rtps/writer/WriterDiscoveryInfo.h>
#include <fastrtps/utils/IPLocator.h>

#include <sstream>

#include "common/security/security_identity.hpp"
#include "common/transport/internal/writer_id.hpp"

namespace fleetmap::transport {
namespace {

using eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
using eprosima::fastrtps::rtps::WriterDiscoveryInfo;

std::string PrefixOf(const eprosima::fastrtps::rtps::GUID_t& guid) {
  eprosima::fastrtps::rtps::InstanceHandle_t handle;
  for (size_t i = 0; i < guid.guidPrefix.size; ++i) handle.value[i] = guid.guidPrefix.value[i];
  return WriterId(handle).substr(0, 24);
}

// The first IPv4 unicast locator's address: metatraffic (discovery) first, then user data.
std::optional<std::string> HostOfParticipant(
    const eprosima::fastrtps::rtps::ParticipantProxyData& data) {
  for (const auto* locators :
       {&data.metatraffic_locators.unicast, &data.default_locators.unicast}) {
    for (const eprosima::fastrtps::rtps::Locator_t& locator : *locators) {
      if (locator.kind == LOCATOR_KIND_UDPv4 || locator.kind == LOCATOR_KIND_TCPv4) {
        return eprosima::fastrtps::rtps::IPLocator::ip_to_string(locator);
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> ParticipantIdentities::HostOf(const std::string& writer_id) const {
  std::lock_guard lock(mutex_);
  const auto it = host_by_prefix_.find(writer_id.substr(0, 24));
  if (it == host_by_prefix_.end()) return std::nullopt;
  return it->second;
}

std::optional<std::string> ParticipantIdentities::NameOf(const std::string& writer_id) const {
  std::lock_guard lock(mutex_);
  const auto it = name_by_prefix_.find(writer_id.substr(0, 24));
  if (it == name_by_prefix_.end()) return std::nullopt;
  return it->second;
}

std::optional<double> ParticipantIdentities::SecondsUntilAuthenticated(
    const std::string& name) const {
  std::lock_guard lock(mutex_);
  std::optional<double> first;
  for (const auto& [prefix, seconds] : authenticated_after_by_prefix_) {
    const auto named = name_by_prefix_.find(prefix);
    if (named == name_by_prefix_.end() || named->second != name) continue;
    if (!first || seconds < *first) first = seconds;
  }
  return first;
}

size_t ParticipantIdentities::RemoteWritersOf(const std::string& topic_name) const {
  std::lock_guard lock(mutex_);
  const auto writers = writers_by_topic_.find(topic_name);
  return writers == writers_by_topic_.end() ? 0 : writers->second.size();
}

void ParticipantIdentities::on_publisher_discovery(
    eprosima::fastdds::dds::DomainParticipant* /*participant*/, WriterDiscoveryInfo&& info) {
  std::ostringstream guid;
  guid << info.info.guid();
  const std::string topic = info.info.topicName().to_string();
  std::lock_guard lock(mutex_);
  switch (info.status) {
    case WriterDiscoveryInfo::DISCOVERED_WRITER:
    case WriterDiscoveryInfo::CHANGED_QOS_WRITER:
      writers_by_topic_[topic].insert(guid.str());
      break;
    case WriterDiscoveryInfo::REMOVED_WRITER:
      if (auto writers = writers_by_topic_.find(topic); writers != writers_by_topic_.end()) {
        writers->second.erase(guid.str());
        if (writers->second.empty()) writers_by_topic_.erase(writers);
      }
      break;
  }
}

void ParticipantIdentities::onParticipantAuthentication(
    eprosima::fastdds::dds::DomainParticipant* /*participant*/,
    eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) {
  if (info.status !=
      eprosima::fastrtps::rtps::ParticipantAuthenticationInfo::AUTHORIZED_PARTICIPANT) {
    return;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - created_).count();
  std::lock_guard lock(mutex_);
  authenticated_after_by_prefix_.emplace(PrefixOf(info.guid), seconds);
}

void ParticipantIdentities::on_participant_discovery(
    eprosima::fastdds::dds::DomainParticipant* /*participant*/, ParticipantDiscoveryInfo&& info) {
  const std::string prefix = PrefixOf(info.info.m_guid);
  std::lock_guard lock(mutex_);
  switch (info.status) {
    case ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT:
    case ParticipantDiscoveryInfo::CHANGED_QOS_PARTICIPANT: {
      if (std::optional<std::string> host = HostOfParticipant(info.info)) {
        host_by_prefix_[prefix] = *std::move(host);
      }
      for (const auto& property : info.info.identity_token_.properties()) {
        if (property.name() == "dds.cert.sn") {
          name_by_prefix_[prefix] = security::CommonNameOfSubject(property.value());
        }
      }
      break;
    }
    case ParticipantDiscoveryInfo::REMOVED_PARTICIPANT:
    case ParticipantDiscoveryInfo::DROPPED_PARTICIPANT:
      name_by_prefix_.erase(prefix);
      host_by_prefix_.erase(prefix);
      authenticated_after_by_prefix_.erase(prefix);
      break;
  }
}

}  // namespace fleetmap::transport

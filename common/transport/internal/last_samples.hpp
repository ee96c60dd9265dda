#pragma once

// Internal to transport: the last sample a writer wrote on each instance, serialized, so that a
// server that starts serving can write its whole state again (served_state.hpp).

#include <fastdds/rtps/common/InstanceHandle.h>
#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <map>
#include <memory>
#include <mutex>

namespace fleetmap::transport {

// Thread-safe: the writer's thread records, another writes everything again.
class LastSamples {
 public:
  explicit LastSamples(eprosima::fastdds::dds::TypeSupport type) : type_(std::move(type)) {}

  // Writes `sample` (of the type) with `writer`, remembered as its instance's last; false when
  // DDS refused it. Recording and writing are one step, so WriteAgain() never writes an older
  // sample after a newer one.
  bool Write(eprosima::fastdds::dds::DataWriter* writer, void* sample);
  // Disposes the instance `key` names, remembered as disposed.
  bool Dispose(eprosima::fastdds::dds::DataWriter* writer, void* key);
  // Writes every remembered instance again (disposes the disposed ones); the number of
  // instances DDS accepted.
  size_t WriteAgain(eprosima::fastdds::dds::DataWriter* writer);
  size_t size() const;

 private:
  struct Last {
    bool disposed = false;
    std::unique_ptr<eprosima::fastrtps::rtps::SerializedPayload_t> payload;
  };

  // The instance `sample` belongs to and its serialized form; false if the type could not
  // serialize it.
  bool Remember(void* sample, bool disposed);

  eprosima::fastdds::dds::TypeSupport type_;
  mutable std::mutex mutex_;
  std::map<eprosima::fastrtps::rtps::InstanceHandle_t, Last> last_;  // guarded by mutex_
};

}  // namespace fleetmap::transport

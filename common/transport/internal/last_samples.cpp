#include "common/transport/internal/last_samples.hpp"

namespace fleetmap::transport {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::InstanceHandle_t;
using eprosima::fastrtps::rtps::SerializedPayload_t;

bool LastSamples::Remember(void* sample, bool disposed) {
  InstanceHandle_t instance;
  if (!type_->getKey(sample, &instance, false)) return false;
  auto payload = std::make_unique<SerializedPayload_t>(type_->getSerializedSizeProvider(sample)());
  if (!type_->serialize(sample, payload.get())) return false;
  Last& last = last_[instance];
  last.disposed = disposed;
  last.payload = std::move(payload);
  return true;
}

bool LastSamples::Write(dds::DataWriter* writer, void* sample) {
  std::lock_guard lock(mutex_);
  if (!writer->write(sample)) return false;
  Remember(sample, false);
  return true;
}

bool LastSamples::Dispose(dds::DataWriter* writer, void* key) {
  std::lock_guard lock(mutex_);
  // HANDLE_NIL: the instance is found from the key (Fast DDS 2.9 lacks lookup_instance).
  if (writer->dispose(key, dds::HANDLE_NIL) != ReturnCode_t::RETCODE_OK) return false;
  Remember(key, true);
  return true;
}

size_t LastSamples::WriteAgain(dds::DataWriter* writer) {
  std::lock_guard lock(mutex_);
  void* sample = type_.create_data();
  size_t written = 0;
  for (auto& [instance, last] : last_) {
    last.payload->pos = 0;
    if (!type_->deserialize(last.payload.get(), sample)) continue;
    const bool ok = last.disposed
                        ? writer->dispose(sample, dds::HANDLE_NIL) == ReturnCode_t::RETCODE_OK
                        : writer->write(sample);
    written += ok;
  }
  type_.delete_data(sample);
  return written;
}

size_t LastSamples::size() const {
  std::lock_guard lock(mutex_);
  return last_.size();
}

}  // namespace fleetmap::transport

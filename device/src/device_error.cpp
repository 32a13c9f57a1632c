#include "palpa/device/device_error.hpp"

namespace palpa::device {

namespace {
std::string join(const std::string& device, const std::string& where, const std::string& reason) {
  std::string line = device;
  line += ": ";
  line += where;
  line += ": ";
  line += reason;
  return line;
}
}  // namespace

DeviceError::DeviceError(const std::string& device, const std::string& where, const std::string& reason)
    : std::runtime_error(join(device, where, reason)) {}

}  // namespace palpa::device

#pragma once
// The one exception of the device layer: a device that cannot be listed, opened or booted.
// what() is one line "DEVICE: WHERE: REASON" (e.g. "falcon:1-4: firmware: ... not found"),
// with what to do about it where there is something to do.
#include <stdexcept>
#include <string>

namespace palpa::device {

class DeviceError : public std::runtime_error {
 public:
  DeviceError(const std::string& device, const std::string& where, const std::string& reason);
};

}  // namespace palpa::device

#pragma once
// The device the haptic engine talks to: a pose in, a force out (SI units). Hardware
// drivers (device/) and the virtual and scripted devices here implement it; the engine
// never knows which one it has.
#include <cstdint>
#include <string>

#include <Eigen/Core>
#include "palpa/vec3.hpp"

namespace palpa::engine {


struct DeviceCapabilities {
  std::string name;
  double max_force = 0.0;  ///< N: the device's own limit (the engine never commands more)
  Vec3 workspace_center = Vec3::Zero();  ///< m, in scene coordinates
  double workspace_radius = 0.0;         ///< m
  bool force_output = false;             ///< false: input only (force shown visually)
};

enum class DeviceStatus : std::uint8_t { Ok, Error, Disconnected };

struct DevicePose {
  Vec3 position = Vec3::Zero();  ///< m, in scene coordinates
  std::uint32_t buttons = 0;
};

/// read() and write_force() run in the haptic thread at every tick: implementations must
/// not allocate, lock or block (a driver exchanges data with its own I/O thread or uses
/// non-blocking transfers).
class Device {
 public:
  virtual ~Device() = default;
  virtual const DeviceCapabilities& capabilities() const = 0;
  /// The pose at time t (s since the engine started).
  virtual DeviceStatus read(double t, DevicePose& pose) noexcept = 0;
  virtual DeviceStatus write_force(const Vec3& force) noexcept = 0;

  /// Where a device with a workspace of its own (a SpaceMouse, a Falcon) sits in the scene:
  /// its workspace centre goes to `scene_center` (m) and one device metre becomes `scale`
  /// scene metres. Called before the haptic loop starts, never while it runs. Devices that
  /// already report scene coordinates (virtual, scripted, replay) ignore it.
  virtual void place_workspace(const Vec3& scene_center, double scale) {
    (void)scene_center;
    (void)scale;
  }
  /// One line saying why the device last reported Error or Disconnected (empty when it has
  /// not), e.g. "SpaceMouse Pro: read failed: the device was unplugged". Not for the haptic
  /// thread: it may allocate and lock.
  virtual std::string fault_message() const { return {}; }
};

}  // namespace palpa::engine

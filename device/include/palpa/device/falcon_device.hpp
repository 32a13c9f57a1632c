#pragma once
// The Novint Falcon as the probe, with force output. connect() boots the firmware
// (falcon_link.hpp); the I/O thread then exchanges one packet each way per haptic period:
// the newest motor torques out, the encoders and buttons in. Until the three axes report
// homed it sends homing mode (red LED) and no torque: the trainee moves the grip all the
// way out and back in once; meanwhile the position stays at the workspace centre (the
// counts mean nothing before homing). The haptic thread turns encoders into a position
// (forward kinematics) and a force into torques (J^T F), passing both through triple
// buffers. A reading no arm can produce keeps the last good position; only a run of them
// (FalconOptions::bad_readings) is an Error. Unplugging shows as Disconnected; a silent or
// failing firmware as Error. Whenever the I/O thread ends, it sends zero torque first (best
// effort), and once the device is not Ok every write_force publishes zero torque.
#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "palpa/device/falcon_kinematics.hpp"
#include "palpa/device/falcon_link.hpp"
#include "palpa/device/falcon_packet.hpp"
#include "palpa/engine/device.hpp"
#include "palpa/engine/triple_buffer.hpp"

namespace palpa::device {

struct FalconOptions {
  std::filesystem::path firmware;  ///< the user's firmware file; empty: it must be running already
  falcon::BootOptions boot{};
  double max_force = 8.0;          ///< N (the Falcon's rated peak force; docs/devices.md)
  double rate_hz = 1000.0;         ///< packets per second
  int silent_exchanges = 100;      ///< exchanges without a packet before the firmware counts as gone
  int bad_readings = 50;           ///< reads in a row with encoders no arm can produce (50 ms) before Error
};

class FalconDevice final : public engine::Device {
 public:
  FalconDevice(std::unique_ptr<UsbTransport> transport, std::string device_id, const FalconOptions& options = {});
  ~FalconDevice() override;  ///< stops the I/O thread (zero torque first)
  FalconDevice(const FalconDevice&) = delete;
  FalconDevice& operator=(const FalconDevice&) = delete;

  /// Uploads the firmware unless it is running already (it keeps running while the Falcon
  /// stays powered, so a second exercise needs no upload); with no firmware file it must be
  /// running. Returns the boot attempts it took (0: found running). Throws DeviceError.
  int connect();
  /// Starts the I/O thread at rate_hz (exchange() in a loop until stopped or failed).
  void start();
  void stop();
  /// One exchange: sends the newest command, takes the packets that came back. False once
  /// the device is gone or failed. Tests call it directly instead of start().
  bool exchange(unsigned timeout_ms = 2);
  /// With the I/O thread started: waits until the three axes report homed. Throws
  /// DeviceError "ID: homing: REASON" when the device fails meanwhile (the reason is its
  /// fault message, never empty) or after timeout_s.
  void wait_homed(double timeout_s);

  engine::DeviceStatus status() const { return status_.load(std::memory_order_acquire); }

  bool homed() const { return homed_.load(std::memory_order_acquire); }
  std::uint64_t packets() const { return packets_.load(std::memory_order_relaxed); }
  std::uint64_t bad_packets() const { return reader_bad_.load(std::memory_order_relaxed); }

  const engine::DeviceCapabilities& capabilities() const override { return caps_; }
  engine::DeviceStatus read(double t, engine::DevicePose& pose) noexcept override;
  engine::DeviceStatus write_force(const palpa::Vec3& force) noexcept override;
  void place_workspace(const palpa::Vec3& scene_center, double scale) override;
  std::string fault_message() const override;

  /// Device frame (falcon_kinematics.hpp) <-> scene, with the placement.
  palpa::Vec3 to_scene(const palpa::Vec3& device_position) const;
  palpa::Vec3 force_to_device(const palpa::Vec3& scene_force) const;
  /// The torque words the haptic thread last asked for (tests).
  std::array<std::int16_t, 3> commanded_torque() const;

 private:
  struct Reading {
    std::array<std::int16_t, 3> encoder{};
    std::uint8_t flags = 0;
    std::uint64_t count = 0;  ///< 0: nothing read yet
  };
  struct Command {
    std::array<std::int16_t, 3> torque{};
  };
  /// Faults found in the haptic thread, which may not allocate: fault_message() words them.
  enum class HapticFault : std::uint8_t { None, BadReadings };
  void fail(engine::DeviceStatus status, const std::string& message);
  void send_zero_torque();
  bool zero_and_stop();  ///< sends zero torque (best effort) and returns false
  void publish_torque(const std::array<std::int16_t, 3>& torque);

  std::unique_ptr<UsbTransport> transport_;
  falcon::FtdiSerial serial_;
  std::string id_;
  FalconOptions options_;
  engine::DeviceCapabilities caps_;
  falcon::Kinematics kinematics_;
  double scale_ = 1.0;
  // I/O thread
  falcon::PacketReader reader_;
  Reading io_reading_;
  int silent_ = 0;
  int failures_ = 0;
  engine::TripleBuffer<Reading> readings_{Reading{}};
  engine::TripleBuffer<Command> commands_{Command{}};
  std::atomic<bool> homed_{false};
  std::atomic<std::uint64_t> packets_{0};
  std::atomic<std::uint64_t> reader_bad_{0};
  std::atomic<engine::DeviceStatus> status_{engine::DeviceStatus::Ok};
  mutable std::mutex message_mutex_;  // I/O and GUI threads only
  std::string fault_message_;
  std::atomic<HapticFault> haptic_fault_{HapticFault::None};
  std::atomic<bool> stop_{false};
  std::thread thread_;
  // haptic thread
  palpa::Vec3 device_position_ = falcon::Kinematics::workspace_center();
  std::uint64_t solved_count_ = 0;  ///< the reading device_position_ was solved from
  bool solved_ = true;              ///< whether that reading had a position
  int bad_readings_ = 0;            ///< reads in a row without one
  std::atomic<std::int16_t> t0_{0}, t1_{0}, t2_{0};
};

}  // namespace palpa::device

#pragma once
// The Falcon firmware's 16-byte packets (docs/devices.md, "Protocol
// protocols"; byte layout as libnifalcon documents it in FalconFirmwareNovintSDK.h):
//
//   '<'  w0 w0 w0 w0  w1 w1 w1 w1  w2 w2 w2 w2  flags  0x41  '>'
//
// Three signed 16-bit words, each as four nibbles, least significant first, every nibble
// offset by 0x41 ('A'..'P'), then a flags byte (also offset by 0x41) and a spare byte.
// Host to device the words are the three motor torques and the flags are homing mode
// (0x01) and the LEDs (0x02 green, 0x04 blue, 0x08 red); device to host the words are the
// three encoder counts and the flags the grip buttons (0x01-0x08) and the homed axes
// (0x10, 0x20, 0x40). Source of the bits: libnifalcon, FalconFirmwareNovintSDK.cpp
// formatInput() (`m_rawInput[13] = m_ledStatus; if (m_homingMode) m_rawInput[13] |= 0x01;`)
// and FalconFirmware.h (GREEN_LED=0x2, BLUE_LED=0x4, RED_LED=0x8); formatOutput() reads the
// homed axes from bits 4-6. Encoding and decoding allocate nothing.
#include <array>
#include <cstddef>
#include <cstdint>

namespace palpa::device::falcon {

inline constexpr std::size_t kPacketSize = 16;
using Packet = std::array<std::uint8_t, kPacketSize>;

// Host to device. (0x10-0x40 are what the device RETURNS for the homed axes: sending 0x10
// as "homing mode" never started homing.)
inline constexpr std::uint8_t kHomingMode = 0x01;
inline constexpr std::uint8_t kLedGreen = 0x02, kLedBlue = 0x04, kLedRed = 0x08;
// Device to host.
inline constexpr std::uint8_t kButtonMask = 0x0F;
inline constexpr std::uint8_t kHomedMask = 0x70;  ///< all three axes homed

struct Words {
  std::array<std::int16_t, 3> value{};
  std::uint8_t flags = 0;
};

void encode(const Words& words, Packet& packet);
/// Null when the packet is well formed, else why not ("no '<' at byte 0", "byte 5 is 0x39,
/// not a nibble ('A'..'P')"): static strings.
const char* decode(const std::uint8_t* packet, Words& words);

/// Cuts the byte stream from the device into packets: bytes come in pieces of any size,
/// a packet may straddle two reads, and garbage before a '<' (or a frame whose 16th byte is
/// not '>') is skipped and counted.
class PacketReader {
 public:
  /// Adds bytes (when the buffer is full the oldest are dropped and counted as skipped).
  void feed(const std::uint8_t* data, std::size_t size);
  /// The oldest complete, well-formed packet, if any.
  bool next(Words& words);
  std::uint64_t skipped_bytes() const { return skipped_; }
  std::uint64_t bad_packets() const { return bad_; }

 private:
  std::array<std::uint8_t, 512> buffer_{};
  std::size_t size_ = 0;
  std::uint64_t skipped_ = 0;
  std::uint64_t bad_ = 0;
};

}  // namespace palpa::device::falcon

#pragma once
// SpaceMouse HID input reports (docs/devices.md, "Protocol notes"):
//  - split layout (vendor 0x046D, and the 0x256F Compact): report 1 = X, Y, Z and report
//    2 = Rx, Ry, Rz, each int16 little-endian in bytes 1-6;
//  - six-axis layout (0x256F wireless models): report 1 = X, Y, Z, Rx, Ry, Rz in bytes 1-12;
//  - both: report 3 = button bitmask, little-endian from byte 1.
// Full scale is about +-350. Parsing allocates nothing (the I/O thread runs it per report).
#include <array>
#include <cstddef>
#include <cstdint>

namespace palpa::device {

enum class ReportLayout : std::uint8_t { Split, SixAxis };

/// The layout a SpaceMouse model sends.
ReportLayout report_layout(std::uint16_t vendor, std::uint16_t product);

/// What the reports say so far: raw axis counts (X, Y, Z, Rx, Ry, Rz) and the buttons.
struct SpaceMouseState {
  std::array<std::int16_t, 6> axes{};
  std::uint32_t buttons = 0;
};

enum class ReportKind : std::uint8_t {
  Translation,  ///< report 1, split layout
  Rotation,     ///< report 2
  SixAxes,      ///< report 1, six-axis layout
  Buttons,      ///< report 3
  Other,        ///< a report the probe has no use for (battery, LEDs, ...): ignored
  Bad,          ///< too short for its id: `state` untouched, `message` says why
};

struct ReportOutcome {
  ReportKind kind = ReportKind::Other;
  std::array<char, 96> message{};  ///< for Bad: "report 1 has 5 bytes, the six-axis layout needs 13"
};

/// Folds one report (report id in byte 0) into `state`.
ReportOutcome parse_report(ReportLayout layout, const std::uint8_t* report, std::size_t size, SpaceMouseState& state);

}  // namespace palpa::device

// Fuzz target: SpaceMouse HID input reports. Byte 0 of the input picks the layout, the rest
// is a stream of reports, each prefixed by its length. A report too short for its id is
// Bad and leaves the state untouched; no report writes outside the state.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "palpa/device/spacemouse_report.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace palpa::device;
  if (size == 0) return 0;
  const ReportLayout layout = (data[0] & 1) != 0 ? ReportLayout::SixAxis : ReportLayout::Split;
  SpaceMouseState state;
  std::size_t at = 1;
  while (at < size) {
    const std::size_t length = std::min<std::size_t>(data[at], size - at - 1);
    const std::uint8_t* report = data + at + 1;
    const SpaceMouseState before = state;
    const ReportOutcome outcome = parse_report(layout, report, length, state);
    if (outcome.kind == ReportKind::Bad || outcome.kind == ReportKind::Other) {
      if (before.axes != state.axes || before.buttons != state.buttons) std::abort();
    }
    if (outcome.kind == ReportKind::Bad && (outcome.message[0] == '\0' || outcome.message.back() != '\0')) std::abort();
    at += 1 + length;
  }
  return 0;
}

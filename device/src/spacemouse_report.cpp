#include "palpa/device/spacemouse_report.hpp"

#include <utility>

#include <fmt/format.h>

#include "palpa/device/device_ids.hpp"

namespace palpa::device {

namespace {

std::int16_t int16_le(const std::uint8_t* p) {
  // Two's complement from two bytes: the cast to int16_t is the sign extension.
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] | (p[1] << 8)));
}

// Into the fixed buffer, cut short and NUL-terminated: parsing a report allocates nothing.
template <typename... Args>
void set_message(ReportOutcome& out, fmt::format_string<Args...> format, Args&&... args) {
  *fmt::format_to_n(out.message.data(), out.message.size() - 1, format, std::forward<Args>(args)...).out = '\0';
}

ReportOutcome bad(const std::uint8_t id, std::size_t size, std::size_t needed, const char* what) {
  ReportOutcome out;
  out.kind = ReportKind::Bad;
  set_message(out, "report {} has {} bytes, {} needs {}", static_cast<unsigned>(id), size, what, needed);
  return out;
}

}  // namespace

const UsbId* find_spacemouse(std::uint16_t vendor, std::uint16_t product) {
  for (const auto& id : kSpaceMouseIds) {
    if (id.vendor == vendor && id.product == product) return &id;
  }
  return nullptr;
}

ReportLayout report_layout(std::uint16_t vendor, std::uint16_t product) {
  return vendor == 0x256F && product != 0xC635 ? ReportLayout::SixAxis : ReportLayout::Split;
}

ReportOutcome parse_report(ReportLayout layout, const std::uint8_t* report, std::size_t size, SpaceMouseState& state) {
  ReportOutcome out;
  if (size == 0 || report == nullptr) {
    out.kind = ReportKind::Bad;
    set_message(out, "empty report");
    return out;
  }
  const std::uint8_t id = report[0];
  switch (id) {
    case 1:
      if (layout == ReportLayout::SixAxis) {
        if (size < 13) return bad(id, size, 13, "the six-axis layout");
        for (std::size_t k = 0; k < 6; ++k) state.axes[k] = int16_le(report + 1 + 2 * k);
        out.kind = ReportKind::SixAxes;
      } else {
        if (size < 7) return bad(id, size, 7, "translation");
        for (std::size_t k = 0; k < 3; ++k) state.axes[k] = int16_le(report + 1 + 2 * k);
        out.kind = ReportKind::Translation;
      }
      return out;
    case 2:
      if (size < 7) return bad(id, size, 7, "rotation");
      for (std::size_t k = 0; k < 3; ++k) state.axes[3 + k] = int16_le(report + 1 + 2 * k);
      out.kind = ReportKind::Rotation;
      return out;
    case 3: {
      if (size < 2) return bad(id, size, 2, "a button mask");
      std::uint32_t mask = 0;
      const std::size_t bytes = size - 1 < 4 ? size - 1 : 4;
      for (std::size_t k = 0; k < bytes; ++k) mask |= static_cast<std::uint32_t>(report[1 + k]) << (8 * k);
      state.buttons = mask;
      out.kind = ReportKind::Buttons;
      return out;
    }
    default:
      out.kind = ReportKind::Other;
      return out;
  }
}

}  // namespace palpa::device

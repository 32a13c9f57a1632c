// palpa-cli devices [--json]: what can be the probe here (the virtual device always, then
// attached SpaceMice and Falcons) with the ids --device takes. Never fails for want of
// /dev/bus/usb or /dev/hidraw*: it says so in a note line and exits 0.
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "palpa/device/registry.hpp"

namespace palpa::cli {
namespace {

int run_devices(bool json) {
  const auto listing = device::list_devices();
  if (json) {
    nlohmann::json out;
    out["devices"] = nlohmann::json::array();
    for (const auto& d : listing.devices) {
      out["devices"].push_back(
          {{"id", d.id}, {"kind", d.kind}, {"name", d.name}, {"force_output", d.force_output}, {"detail", d.detail}});
    }
    out["notes"] = listing.notes;
    std::printf("%s\n", out.dump(2).c_str());
    return kOk;
  }
  std::printf("%-28s %-11s %-36s %-6s %s\n", "ID", "KIND", "NAME", "FORCE", "WHERE");
  for (const auto& d : listing.devices) {
    std::printf("%-28s %-11s %-36s %-6s %s\n", d.id.c_str(), d.kind.c_str(), d.name.c_str(),
                d.force_output ? "yes" : "no", d.detail.empty() ? "-" : d.detail.c_str());
  }
  for (const auto& note : listing.notes) std::printf("note: %s\n", note.c_str());
  return kOk;
}

}  // namespace

Command add_devices_command(CLI::App& parent) {
  auto json = std::make_shared<bool>(false);
  auto* app = parent.add_subcommand(
      "devices",
      "List the devices that can be the probe: the virtual device (the mouse) and any attached 3Dconnexion SpaceMouse "
      "or Novint Falcon, with the ID that --device takes (exercise, simulate; palpa --device). Notes say why a "
      "device could not be looked for (no /dev/bus/usb, no permission: see docs/devices.md).");
  app->add_flag("--json", *json, "print the list as JSON: {\"devices\": [{id, kind, name, force_output, detail}], \"notes\": []}");
  return {app, [json] { return run_devices(*json); }};
}

}  // namespace palpa::cli

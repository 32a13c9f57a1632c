#include "output_guard.hpp"

#include <system_error>

namespace palpa::cli {
namespace {

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return !a.empty() && !b.empty() && std::filesystem::equivalent(a, b, ec) && !ec;
}

}  // namespace

std::string refusal_to_write(const std::filesystem::path& output, bool force,
                             const std::vector<std::filesystem::path>& inputs) {
  for (const auto& input : inputs) {
    if (same_file(output, input)) {
      return output.string() + ": is also an input of this command (" + input.string() +
             "); refusing to write over it, even with --force";
    }
  }
  std::error_code ec;
  if (!force && std::filesystem::exists(output, ec)) {
    return output.string() + ": exists; give --force to replace it";
  }
  return {};
}

std::string refusal_to_write(const std::vector<std::filesystem::path>& outputs, bool force,
                             const std::vector<std::filesystem::path>& inputs) {
  for (const auto& output : outputs) {
    if (auto why = refusal_to_write(output, force, inputs); !why.empty()) return why;
  }
  return {};
}

}  // namespace palpa::cli

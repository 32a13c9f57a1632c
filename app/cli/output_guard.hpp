#pragma once
// palpa-cli never writes over a user's file unless told to: an output that exists is
// refused without --force, and an output that is one of the command's own inputs (the same
// file by any path) is refused even with it.
#include <filesystem>
#include <string>
#include <vector>

namespace palpa::cli {

/// Why `output` may not be written, as one line naming it and what to do; empty when it may.
std::string refusal_to_write(const std::filesystem::path& output, bool force,
                             const std::vector<std::filesystem::path>& inputs);

/// The first refusal among `outputs`, or empty.
std::string refusal_to_write(const std::vector<std::filesystem::path>& outputs, bool force,
                             const std::vector<std::filesystem::path>& inputs);

}  // namespace palpa::cli

#pragma once
#include "commands.hpp"
// palpa-cli exercise --device replay:SESSION (see exercise_replay.cpp).
#include <string>

namespace palpa::cli {

/// Replays SESSION's probe path through the engine into a new session at out_path and
/// scores it; `trainee` empty keeps the recorded one. Returns the exit code.
int run_replay_exercise(const std::string& session_path, const std::string& trainee, const std::string& out_path,
                        bool json, const ReportRequest& report);

}  // namespace palpa::cli

// Link-time fallback for session::SessionError's constructor while core/src/session is
// written in parallel (issue 6): weak, so the real definition in core/src/session wins
// as soon as it is linked. Delete this file once core/src/session/session.cpp defines it.
#include "palpa/session/session.hpp"

namespace palpa::session {

__attribute__((weak)) SessionError::SessionError(std::string file, std::string where, std::string reason)
    : std::runtime_error(file + ": " + where + ": " + reason),
      file_(std::move(file)),
      where_(std::move(where)),
      reason_(std::move(reason)) {}

}  // namespace palpa::session

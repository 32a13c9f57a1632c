#pragma once
// Session ids (docs/session-format.md, "Session ids"): 32 lowercase hex digits (128 random
// bits) for every session Palpa records; 16 digits in scripted sessions recorded before
// that rule, which still read and push.
#include <string>
#include <string_view>

namespace palpa::session {

/// A new id: 32 lowercase hex digits from std::random_device.
std::string new_session_id();

/// True for 32 (or, from older scripted sessions, 16) lowercase hex digits: the only ids the
/// centre store accepts, and so the only ones that ever become part of a file name.
bool is_session_id(std::string_view id);

}  // namespace palpa::session

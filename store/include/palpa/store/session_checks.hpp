#pragma once
// The limits the centre store holds every pushed session to (docs/security.md, "What the
// server checks"), checked here too so that a session the server would refuse is refused
// before anything is queued in the outbox: its id becomes an outbox file name. The server
// checks again (palpa_check_session): a station is never trusted to have run this.
#include <string>
#include <string_view>

#include "palpa/store/push.hpp"

namespace palpa::store {

inline constexpr std::size_t kMaxStationChars = 64;
inline constexpr std::size_t kMaxTraineeChars = 128;
inline constexpr std::size_t kMaxFileNameChars = 255;
inline constexpr std::size_t kMaxCaseTitleChars = 200;

/// The modes the store accepts (session::session_mode; docs/session-format.md "Modes").
bool is_known_mode(std::string_view mode);

/// Empty when `value` may be stored as text field `field` of at most `max_chars`
/// characters; else why not ("field trainee: holds a control character").
std::string text_problem(std::string_view field, std::string_view value, std::size_t max_chars);

/// Throws StoreError (not unreachable) naming the file and the field when the store would
/// refuse `s`: its id, trainee, file name, case title, mode, start date or sample count.
void check_pushable(const PreparedSession& s);

/// Throws StoreError when `station` is no name the store accepts: 1 to 64 of A-Z a-z 0-9,
/// space, dot, underscore and dash, starting with a letter or digit.
void check_station_name(const std::string& station);

}  // namespace palpa::store

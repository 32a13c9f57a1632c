#pragma once
// What a report says about the session itself (who, which case, which device, when, which
// file): everything but the samples, so a batch can keep it for every session it scored.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "palpa/session/session.hpp"

namespace palpa::report {

struct SessionHeader {
  std::string id;
  std::string trainee;
  std::string case_title;   ///< the case document's "title" (may be empty)
  std::string case_source;  ///< the case file as named when the session started
  std::string device;
  std::string software_version;
  std::string started_at;   ///< ISO 8601 UTC
  std::string file;         ///< the session file as given to the command
  std::string mode;         ///< session::session_mode: trainee, instructor-try, scripted, replay, ...
  std::string case_file;    ///< the case file's name (case_source without its folder)
  std::string case_id;      ///< case_activity_id: the case's stable id in reports and xAPI
  std::string station;      ///< extra.station: the station that recorded it; empty when not recorded
};

SessionHeader header_of(const session::SessionInfo& info, const std::filesystem::path& file);

/// The "session" object of the report JSON: id, trainee, case (the title), case_source,
/// device, software_version, started_at, file.
nlohmann::json to_json(const SessionHeader& header);

/// Lower-case ASCII letters and digits, other runs turned into one '-', at most 64
/// characters; empty when the text has no letter or digit.
std::string slug(std::string_view text);

/// A stable activity IRI for the case: "urn:palpa:case:" + slug of the title, or of the
/// case file's stem when the title has none, or "sha1-" + 12 hex digits of the title.
std::string case_activity_id(const SessionHeader& header);

/// A readable case name: the title, else the case file's name.
std::string case_name(const SessionHeader& header);

}  // namespace palpa::report

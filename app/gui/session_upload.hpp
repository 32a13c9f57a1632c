#pragma once
// After a trainee's exercise: the session to the centre store and its xAPI statement to
// the learning record store, each when configured (docs/centre.md). Whatever cannot be
// sent now waits in its outbox for the next exercise or `palpa-cli store push` / `lrs flush`.
// Blocking (network): the window runs it off the GUI thread.
#include <filesystem>
#include <string>

#include <QString>

#include "palpa/score/score.hpp"

namespace palpa::gui {

/// This station's name as the store knows it (PALPA_STATION, the store config file, else the
/// host name), recorded in each session's extra.station; empty when the config file is bad
/// (the upload then says why).
std::string station_name();

/// What became of one destination.
enum class UploadState { NotConfigured, Sent, Waiting, Failed };

struct UploadOutcome {
  UploadState store = UploadState::NotConfigured;
  UploadState lrs = UploadState::NotConfigured;
  int store_waiting = 0;  ///< sessions in the store outbox afterwards
  int lrs_waiting = 0;    ///< statements in the xAPI outbox afterwards
  std::string store_detail, lrs_detail;  ///< the reason when waiting or failed (one line)
};

/// Uploads the session at `path` (scored as `score`, when it was) as configured by
/// PALPA_STORE / ~/.config/palpa/store.json and PALPA_LRS / ~/.config/palpa/lrs.json.
/// Never throws; never removes or changes the session file.
UploadOutcome upload_finished_session(const std::filesystem::path& path, const score::Score* score);

/// One line for the status bar, in words ("Centre store: uploaded. LRS: sent."); empty when
/// neither is configured.
QString upload_status_text(const UploadOutcome& outcome);

}  // namespace palpa::gui

#pragma once
// A finished session's xAPI statement on its way to the centre's learning record store:
// queued in the station's outbox, then sent (palpa-cli score --lrs, exercise).
#include <optional>
#include <string>

#include "commands.hpp"
#include "palpa/lrs/lrs_config.hpp"
#include "palpa/report/session_header.hpp"
#include "palpa/score/score.hpp"

namespace palpa::cli {

/// The LRS settings a report request needs (its homePage even when nothing is sent);
/// nullopt after printing one line when the config file is malformed.
std::optional<lrs::LrsConfig> xapi_settings(const ReportRequest& request);

/// Queues the statement and sends the outbox when `request` asks for it (--lrs) or, with
/// request.lrs_when_configured, whenever an LRS is configured. Prints one line on stderr.
/// Returns kOk when sent or safely queued (the LRS unreachable), kFailure when the LRS
/// rejected it or it could not be queued.
int send_statement(const report::SessionHeader& header, const score::Score& score, const ReportRequest& request,
                   const lrs::LrsConfig& config);

}  // namespace palpa::cli

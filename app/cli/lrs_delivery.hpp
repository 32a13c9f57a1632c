#pragma once
// Sending a station's outbox to its LRS with one line of outcome on stderr, shared by
// `palpa-cli lrs` and the commands that finish sessions (score, exercise with --lrs).
#include "palpa/lrs/lrs_config.hpp"
#include "palpa/lrs/statement_outbox.hpp"

namespace palpa::cli {

/// Exit code 3: some statements still wait in the outbox (the LRS is unreachable).
inline constexpr int kQueued = 3;

/// Delivers the outbox to config.endpoint; prints "lrs: ..." on stderr. Returns kOk when the
/// outbox is empty afterwards, kQueued when statements wait, kBadInput when the LRS rejected
/// some, kBadInput too when no endpoint is configured (the statements stay queued).
int deliver_outbox(const lrs::LrsConfig& config, lrs::StatementOutbox& outbox, int attempts);

}  // namespace palpa::cli

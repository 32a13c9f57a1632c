#pragma once
// The station's xAPI outbox: a folder holding each statement that has not yet reached the
// learning record store, one file ID.json per statement (written to a temporary name and
// renamed, so a crash leaves either the whole file or none). A statement leaves the folder
// only when the LRS has answered that it holds it; one the LRS refuses moves to
// rejected/ID.json with the reason beside it (ID.reason.txt), for a person to look at.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "palpa/lrs/lrs_client.hpp"

namespace palpa::lrs {

struct OutboxEntry {
  std::filesystem::path file;
  std::string statement_id;
  std::string actor;      ///< the account name (the trainee id)
  std::string timestamp;  ///< the statement's timestamp (the session's start)
  std::string last_error; ///< why the last attempt failed; empty before the first attempt
  bool rejected = false;  ///< in rejected/: the LRS refused it
};

struct FlushReport {
  int stored = 0;
  int rejected = 0;
  int waiting = 0;           ///< still in the outbox (unreachable LRS)
  std::string last_reason;   ///< of the last failure, for the one-line summary
};

/// How one statement is sent: put_statement in production, a fake in tests.
using Sender = std::function<SendResult(const nlohmann::json&)>;

class StatementOutbox {
 public:
  /// Creates the folder when needed; throws std::runtime_error naming it when that fails.
  explicit StatementOutbox(std::filesystem::path folder);

  const std::filesystem::path& folder() const { return folder_; }

  /// Adds a statement (replacing a waiting one with the same id); throws when it cannot be
  /// written, naming the file.
  std::filesystem::path add(const nlohmann::json& statement);

  /// The statements waiting, oldest file first, then the rejected ones.
  std::vector<OutboxEntry> list() const;

  /// Tries every waiting statement once, in order; stops trying once the LRS is unreachable
  /// (the rest stay for later). Stored ones are removed, rejected ones moved aside.
  FlushReport flush(const Sender& send);

 private:
  void record_failure(const std::filesystem::path& file, const SendResult& result) const;
  void reject(const std::filesystem::path& file, const SendResult& result) const;

  std::filesystem::path folder_;
};

/// The default outbox: $XDG_DATA_HOME/palpa/xapi-outbox, else ~/.local/share/palpa/xapi-outbox.
std::filesystem::path default_outbox_folder();

}  // namespace palpa::lrs

namespace palpa::lrs {

/// Flushes the outbox to `endpoint` with up to `attempts` tries while the LRS is
/// unreachable, waiting 0.5 s, 1 s, 2 s, ... between them (the statements stay in the outbox
/// when every try fails: the next send or `palpa-cli lrs flush` tries again).
FlushReport deliver(StatementOutbox& outbox, const std::string& endpoint, int attempts = 3, double timeout_s = 10.0);

}  // namespace palpa::lrs

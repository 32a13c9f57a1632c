// palpa-cli store init|push|status|enrol: the centre store on PostgreSQL (docs/centre.md).
// init creates or migrates the schema; push uploads finished sessions, queueing them in the
// station's outbox when the server cannot be reached; status lists what waits there; enrol
// says which stations may push for a trainee.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "isolated_score.hpp"
#include "palpa/report/printable.hpp"
#include "palpa/store/catalog.hpp"
#include "palpa/store/config.hpp"
#include "palpa/store/outbox.hpp"
#include "palpa/store/push.hpp"
#include "palpa/store/schema.hpp"
#include "palpa/store/session_checks.hpp"

namespace palpa::cli {
namespace {

namespace fs = std::filesystem;

struct StoreOptions {
  std::string url;  ///< init: the positional URL
  std::vector<std::string> sessions;
  std::string store, station, outbox;
  bool outbox_only = false;
  std::vector<std::string> trainees;  ///< enrol
  bool remove = false;                ///< enrol: end the enrolments
  int schema_version = 0;  ///< init: stop at this version (0: the newest)
};

// Lines carry names from session files and the store: escaped (report/printable.hpp).
void say(const std::string& line) { std::printf("%s\n", report::printable(line, 1000).c_str()); }

int run_init(const StoreOptions& o) {
  try {
    store::Connection c(o.url);
    const auto r = store::init_schema(c, o.schema_version);
    if (r.from == r.to) {
      say(fmt::format("store: {}: schema version {}, already up to date", c.target(), r.to));
    } else {
      say(fmt::format("store: {}: schema version {} (was {})", c.target(), r.to, r.from));
    }
    if (r.large_objects_open) {
      std::fputs("palpa-cli: warning: any login can create large objects in this database (outside every table and "
                 "quota); only a superuser can revoke that: sudo -u postgres psql -d DBNAME -c \"REVOKE EXECUTE ON "
                 "FUNCTION lo_create(oid), lo_creat(integer), lo_from_bytea(oid, bytea), lo_import(text), "
                 "lo_import(text, oid) FROM PUBLIC\" (docs/centre.md, section 1)\n",
                 stderr);
    }
    return kOk;
  } catch (const store::StoreError& e) {
    print_error(e.what());
    return kFailure;
  }
}

std::optional<store::StoreSettings> settings_of(const StoreOptions& o, bool need_store) {
  try {
    auto s = store::resolve_settings(o.store, o.station, o.outbox);
    store::check_station_name(s.station);
    if (need_store && s.conninfo.empty()) {
      print_error(fmt::format("no store configured: give --store, set PALPA_STORE or write \"store\" in {}",
                              store::config_path().string()));
      return std::nullopt;
    }
    return s;
  } catch (const store::StoreError& e) {
    print_error(e.what());
    return std::nullopt;
  }
}

// Queues `p` in the outbox because of `why`; false when even the outbox cannot take it.
bool queue(const store::StoreSettings& s, const store::PreparedSession& p, const std::string& why) {
  try {
    const auto e = store::queue_session(s.outbox, p, why);
    say(fmt::format("queued: {} in {} ({})", p.path.string(), e.file.string(), why));
    return true;
  } catch (const store::StoreError& e) {
    print_error(fmt::format("{}: not pushed and not queued: {}", p.path.string(), e.what()));
    return false;
  }
}

// Queues `p` unless the same session waits already; kOk, or the exit code of a failure.
int queue_unless_waiting(const store::StoreSettings& s, const store::PreparedSession& p, const std::string& why) {
  try {
    if (store::is_queued(s.outbox, p)) {
      say(fmt::format("already queued: {} ({})", p.path.string(), why));
      return kOk;
    }
  } catch (const store::StoreError& e) {  // another file under its id: never replaced
    print_error(e.what());
    return kBadInput;
  }
  return queue(s, p, why) ? kOk : kFailure;
}

// The store runs a newer schema than this Palpa: nothing can be pushed until the station is
// upgraded, but nothing is lost either: the sessions wait in the outbox.
int queue_for_upgrade(const store::StoreSettings& s, const std::vector<store::PreparedSession>& all,
                      const std::string& why) {
  int code = kQueuedForUpgrade;
  for (const auto& p : all) {
    if (const int queued = queue_unless_waiting(s, p, why); queued != kOk) code = queued;
  }
  print_error(why + "; the sessions wait in the outbox until this station runs the newer Palpa");
  return code;
}

void report_flush(const store::FlushResult& r) {
  for (const auto& e : r.errors) print_error("outbox: " + e);
  if (r.sent + r.waiting > 0) say(fmt::format("outbox: {} sent, {} waiting", r.sent, r.waiting));
}

// Pushes the prepared sessions over `c`; a broken connection queues the rest.
int push_all(store::Connection& c, const store::StoreSettings& s, const std::vector<store::PreparedSession>& all) {
  int code = kOk;
  std::string broken;
  for (const auto& p : all) {
    if (!broken.empty()) {
      if (!queue(s, p, broken)) code = kFailure;
      continue;
    }
    try {
      const auto r = store::push_prepared(c, p, s.station);
      say(fmt::format("{}: {} (session {}, sha-256 {})",
                      r.status == store::PushStatus::Stored ? "stored" : "already stored", p.path.string(),
                      r.session_id, r.sha256));
    } catch (const store::StoreError& e) {
      if (e.unreachable()) {
        broken = e.what();
        if (!queue(s, p, broken)) code = kFailure;
      } else {
        print_error(e.what());
        if (code == kOk) code = kBadInput;
      }
    }
  }
  return code;
}

int run_push(const StoreOptions& o) {
  const auto s = settings_of(o, true);
  if (!s) return kBadInput;
  if (!o.outbox_only && o.sessions.empty()) {
    print_error("store push: give SESSION files, or --outbox-only to send what the outbox holds");
    return kBadInput;
  }
  int code = kOk;
  std::vector<store::PreparedSession> prepared;
  for (const auto& path : o.sessions) {
    try {
      prepared.push_back(store::prepare_session(path));
    } catch (const store::StoreError& e) {
      print_error(e.what());
      code = kBadInput;
    }
  }
  std::unique_ptr<store::Connection> c;
  try {
    c = std::make_unique<store::Connection>(s->conninfo);
    store::check_schema(*c);
  } catch (const store::NewerSchemaError& e) {
    return queue_for_upgrade(*s, prepared, e.what());
  } catch (const store::StoreError& e) {
    if (!e.unreachable()) {
      print_error(e.what());
      return kFailure;
    }
    // The entries already waiting count this attempt; the ones queued now start at 1.
    store::mark_unreachable(s->outbox, e.what());
    for (const auto& p : prepared) {
      if (const int queued = queue_unless_waiting(*s, p, e.what()); queued != kOk && code != kFailure) code = queued;
    }
    if (prepared.empty()) say(fmt::format("outbox: not sent ({})", e.what()));
    return code;
  }
  const int pushed = push_all(*c, *s, prepared);
  if (pushed != kOk && code == kOk) code = pushed;
  report_flush(store::flush_outbox(*c, s->outbox, s->station));
  return code;
}

void print_outbox(const store::StoreSettings& s) {
  const auto entries = store::list_outbox(s.outbox);
  say(fmt::format("outbox {}: {} waiting", s.outbox.string(), entries.size()));
  for (const auto& e : entries) {
    say(fmt::format("  {}  trainee {}  started {}  {} bytes  queued {}  attempts {}", e.file.filename().string(),
                    e.trainee, e.started_at, e.size, e.queued_at, e.attempts));
    if (!e.source.empty()) say("    from: " + e.source);
    if (!e.last_error.empty()) say("    last error: " + e.last_error);
  }
}

int run_status(const StoreOptions& o) {
  const auto s = settings_of(o, false);
  if (!s) return kBadInput;
  say(fmt::format("station: {}", s->station));
  print_outbox(*s);
  if (s->conninfo.empty()) {
    say("store: none configured (--store, PALPA_STORE or " + store::config_path().string() + ")");
    return kOk;
  }
  try {
    store::Connection c(s->conninfo);
    store::check_schema(c);
    long long total = 0;
    std::string by_station;
    for (const auto& n : store::my_session_counts(c)) {
      total += n.sessions;
      by_station += fmt::format("{}{} from {}", by_station.empty() ? "" : ", ", n.sessions, n.station);
    }
    say(fmt::format("store {}: {} sessions stored by this login{}", c.target(), total,
                    by_station.empty() ? "" : " (" + by_station + ")"));
    return kOk;
  } catch (const store::StoreError& e) {
    say(e.what());
    return e.unreachable() ? kOk : kFailure;
  }
}

int run_enrol(const StoreOptions& o) {
  if (o.store.empty() || o.station.empty()) {
    print_error("store enrol: give --store URL (a coordinator's login) and --station NAME");
    return kBadInput;
  }
  int code = kOk;
  try {
    store::Connection c(o.store);
    store::check_schema(c);
    for (const auto& trainee : o.trainees) {
      try {
        const bool changed = store::enrol(c, trainee, o.station, !o.remove);
        say(fmt::format("{}: trainee {} at station {}{}", o.remove ? "not enrolled" : "enrolled", trainee, o.station,
                        changed ? "" : " (already so)"));
      } catch (const store::StoreError& e) {
        if (e.unreachable()) throw;
        print_error(e.what());
        code = kBadInput;
      }
    }
  } catch (const store::StoreError& e) {
    print_error(e.what());
    return kFailure;
  }
  return code;
}

void add_station_options(CLI::App* app, StoreOptions& o) {
  app->add_option("--store", o.store,
                  "libpq connection string or URI (passwords: ~/.pgpass or a service file, never here); default "
                  "PALPA_STORE, then \"store\" in $XDG_CONFIG_HOME/palpa/store.json");
  app->add_option("--station", o.station, "this station's name; default PALPA_STATION, the config file, the host name");
  app->add_option("--outbox", o.outbox,
                  "outbox folder; default PALPA_OUTBOX, the config file, $XDG_DATA_HOME/palpa/outbox "
                  "(~/.local/share/palpa/outbox)");
}

}  // namespace

Command add_store_command(CLI::App& parent) {
  auto o = std::make_shared<StoreOptions>();
  auto* app = parent.add_subcommand("store", "The centre store on PostgreSQL (docs/centre.md): init, push, status, enrol.");
  app->require_subcommand(1);
  auto* init = app->add_subcommand("init", "Create or migrate the store's schema and its roles (as the database owner).");
  init->add_option("URL", o->url, "libpq connection string or URI of the database")->required();
  init->add_option("--schema-version", o->schema_version,
                   "stop at this schema version (to test a migration from an older store); default: the newest")
      ->check(CLI::Range(1, store::known_schema_version()));
  auto* push = app->add_subcommand(
      "push", "Upload finished sessions (idempotent by session id, verified by SHA-256); when the server cannot be "
              "reached they are copied into the outbox. Then sends what the outbox holds.");
  push->add_option("SESSION", o->sessions, "session files (.palpa)");
  push->add_flag("--outbox-only", o->outbox_only, "only send what the outbox holds");
  add_station_options(push, *o);
  auto* status = app->add_subcommand("status", "List the outbox and, when the store is reachable, this login's uploads.");
  add_station_options(status, *o);
  auto* enrol = app->add_subcommand(
      "enrol", "Enrol trainees at a station (a coordinator's login): that station's pushes for them count in the "
               "learning curves; a push from a station a trainee is not enrolled at is flagged, or refused when "
               "store_settings.enrolment is 'refuse'. A new trainee is enrolled at the station that first pushes "
               "for them.");
  enrol->add_option("TRAINEE", o->trainees, "trainee ids, as in the session files")->required();
  enrol->add_option("--station", o->station, "the station's name")->required();
  enrol->add_option("--store", o->store, "libpq connection string or URI, as a palpa_coordinator login")->required();
  enrol->add_flag("--remove", o->remove, "end these enrolments instead");
  // The scoring child of batch --store --worker (isolated_score.hpp); not for people.
  auto* score_claim = app->add_subcommand("score-claim", "internal: a worker's scoring child process");
  score_claim->group("");
  return {app, [o, init, push, enrol, score_claim] {
            if (score_claim->parsed()) return run_score_child();
            if (enrol->parsed()) return run_enrol(*o);
            if (init->parsed()) return run_init(*o);
            if (push->parsed()) return run_push(*o);
            return run_status(*o);
          }};
}

}  // namespace palpa::cli

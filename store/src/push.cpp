#include "palpa/store/push.hpp"

#include <fmt/format.h>

#include "palpa/report/printable.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/store/session_checks.hpp"
#include "palpa/store/sha256.hpp"

namespace palpa::store {
namespace {

namespace fs = std::filesystem;

nlohmann::json events_json(const std::vector<session::Event>& events) {
  auto all = nlohmann::json::array();
  for (const auto& e : events) {
    nlohmann::json event{{"t", e.t}, {"kind", std::string(session::to_string(e.kind))}, {"note", e.note}};
    if (e.mark >= 0) event["mark"] = e.mark;
    if (e.kind == session::EventKind::Mark) event["position"] = e.position;
    all.push_back(std::move(event));
  }
  return all;
}

}  // namespace

std::string shown(const fs::path& path) { return report::printable(path.string(), 200); }

PreparedSession prepare_session(const fs::path& path) {
  std::error_code ec;
  auto wal = path;
  wal += "-wal";
  if (fs::file_size(wal, ec) > 0 && !ec) {
    throw StoreError(fmt::format("{}: has a -wal beside it: still being recorded (or open in another program); "
                                 "not pushed",
                                 shown(path)),
                     false);
  }
  PreparedSession p;
  p.path = path;
  p.file_name = path.filename().string();
  p.bytes = read_file_bytes(path);
  // Read as a stream: every sample checked, none kept (a long session needs no more memory).
  session::Session s;
  std::uint64_t samples = 0;
  try {
    session::SampleStream stream(path);
    while (!stream.next().empty()) {
    }
    s = stream.head();
    samples = stream.count();
  } catch (const session::SessionError& e) {
    throw StoreError(e.what(), false);
  }
  if (!s.complete) {
    throw StoreError(fmt::format("{}: session incomplete (no end event: still recording or cut short); not pushed",
                                 shown(path)),
                     false);
  }
  p.sha256 = sha256_hex(p.bytes);
  p.session_id = s.info.id;
  p.trainee = s.info.trainee;
  p.started_at = s.info.started_at;
  p.mode = session::session_mode(s.info);
  p.case_document = s.info.case_document;
  p.case_title = s.info.case_document.value("title", std::string());
  p.events = events_json(s.events);
  p.complete = s.complete;
  p.samples = samples;
  check_pushable(p);
  return p;
}

PushResult push_prepared(Connection& c, const PreparedSession& p, const std::string& station) {
  Transaction t(c);
  const auto r = c.exec(fmt::format("push {}", shown(p.path)),
                        "SELECT stored, server_sha256 FROM public.palpa_push_session($1, $2, $3, $4, $5::jsonb, "
                        "$6::timestamptz, $7, $8::boolean, $9::bigint, $10, $11::jsonb, $12::bytea)",
                        {Param::text(station), Param::text(p.session_id), Param::text(p.trainee),
                         Param::text(p.case_title), Param::text(p.case_document.dump()),
                         Param::text(p.started_at), Param::text(p.mode), Param::text(p.complete ? "true" : "false"),
                         Param::text(std::to_string(p.samples)), Param::text(p.file_name),
                         Param::text(p.events.dump()), Param::bytes(p.bytes)});
  PushResult result;
  result.status = r.text(0, 0) == "t" ? PushStatus::Stored : PushStatus::AlreadyStored;
  result.session_id = p.session_id;
  result.sha256 = r.text(0, 1);
  if (result.sha256 != p.sha256) {
    throw StoreError(fmt::format("{}: session {} {} with SHA-256 {}, the file has {}; nothing changed",
                                 shown(p.path), p.session_id,
                                 result.status == PushStatus::Stored ? "was stored" : "is already stored",
                                 result.sha256, p.sha256),
                     false);
  }
  t.commit();
  return result;
}

PushResult push_session(Connection& c, const fs::path& path, const std::string& station) {
  return push_prepared(c, prepare_session(path), station);
}

}  // namespace palpa::store

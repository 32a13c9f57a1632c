#include "session_upload.hpp"

#include <exception>

#include <QCoreApplication>
#include <QStringList>

#include "palpa/lrs/lrs_config.hpp"
#include "palpa/lrs/statement_outbox.hpp"
#include "palpa/report/session_header.hpp"
#include "palpa/report/xapi.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/store/config.hpp"
#include "palpa/store/outbox.hpp"
#include "palpa/store/push.hpp"

namespace palpa::gui {
namespace {

// The store: send what waits in the outbox, then this session; queue it when the server
// cannot be reached.
void upload_to_store(const std::filesystem::path& path, UploadOutcome& out) {
  const store::StoreSettings settings = store::resolve_settings("", "", "");
  if (settings.conninfo.empty()) return;
  const store::PreparedSession prepared = store::prepare_session(path);
  try {
    store::Connection c(settings.conninfo);
    store::flush_outbox(c, settings.outbox, settings.station);
    store::push_prepared(c, prepared, settings.station);
    out.store = UploadState::Sent;
  } catch (const store::StoreError& e) {
    if (!e.unreachable()) throw;
    store::queue_session(settings.outbox, prepared, e.what());
    out.store = UploadState::Waiting;
    out.store_detail = e.what();
  }
  out.store_waiting = static_cast<int>(store::list_outbox(settings.outbox).size());
}

// The LRS: queue the statement, then send the outbox (two tries: the window is waiting).
void send_to_lrs(const std::filesystem::path& path, const score::Score& score, UploadOutcome& out) {
  const lrs::LrsConfig config = lrs::load_lrs_config();
  if (config.endpoint.empty()) return;
  session::ReadOptions header_only;
  header_only.samples = false;
  const auto session = session::read_session(path, header_only);
  lrs::StatementOutbox outbox(config.outbox);
  outbox.add(report::xapi_statement(report::header_of(session.info, path), score, config.home_page));
  const lrs::FlushReport r = lrs::deliver(outbox, config.endpoint, 2, 5.0);
  out.lrs = r.waiting > 0 ? UploadState::Waiting : (r.rejected > 0 ? UploadState::Failed : UploadState::Sent);
  out.lrs_waiting = r.waiting;
  out.lrs_detail = r.last_reason;
}

QString state_words(UploadState state, int waiting, const std::string& detail, const QString& sent) {
  const QString why = QString::fromStdString(detail);
  switch (state) {
    case UploadState::Sent: return sent;
    case UploadState::Waiting:
      return QCoreApplication::translate("palpa::gui::upload", "%n waiting in the outbox, sent after the next exercise (%1)",
                                         nullptr, waiting).arg(why);
    case UploadState::Failed: return QCoreApplication::translate("palpa::gui::upload", "not sent: %1").arg(why);
    default: return {};
  }
}

}  // namespace

std::string station_name() {
  try {
    return store::resolve_settings("", "", "").station;
  } catch (const std::exception&) {
    return {};
  }
}

UploadOutcome upload_finished_session(const std::filesystem::path& path, const score::Score* score) {
  UploadOutcome out;
  try {
    upload_to_store(path, out);
  } catch (const std::exception& e) {
    out.store = UploadState::Failed;
    out.store_detail = e.what();
  }
  if (!score) return out;  // no score, no statement (the session ended unscored)
  try {
    send_to_lrs(path, *score, out);
  } catch (const std::exception& e) {
    out.lrs = UploadState::Failed;
    out.lrs_detail = e.what();
  }
  return out;
}

QString upload_status_text(const UploadOutcome& o) {
  const auto tr = [](const char* text) { return QCoreApplication::translate("palpa::gui::upload", text); };
  QStringList parts;
  if (o.store != UploadState::NotConfigured)
    parts << tr("Centre store: %1.").arg(state_words(o.store, o.store_waiting, o.store_detail, tr("uploaded")));
  if (o.lrs != UploadState::NotConfigured)
    parts << tr("Learning record store: %1.").arg(state_words(o.lrs, o.lrs_waiting, o.lrs_detail, tr("sent")));
  return parts.join(' ');
}

}  // namespace palpa::gui

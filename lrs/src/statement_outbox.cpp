#include "palpa/lrs/statement_outbox.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <fmt/format.h>

namespace palpa::lrs {
namespace fs = std::filesystem;
namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Writes `text` to `file` through a temporary name and a rename: all or nothing.
void write_atomically(const fs::path& file, const std::string& text) {
  const fs::path temporary = file.string() + fmt::format(".tmp-{}", ::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the statement", temporary.string()));
  }
  std::error_code error;
  fs::rename(temporary, file, error);
  if (error) {
    fs::remove(temporary, error);
    throw std::runtime_error(fmt::format("{}: cannot write the statement", file.string()));
  }
}

// The statement file names must stay inside the folder: ids are UUIDs, but check anyway.
std::string file_stem_for(const nlohmann::json& statement) {
  const std::string id = statement.value("id", std::string());
  const bool safe = !id.empty() && id.size() <= 64 && std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F') || c == '-';
  });
  if (!safe) throw std::runtime_error("xAPI statement: id: not a UUID");
  return id;
}

fs::path error_file_of(const fs::path& statement_file) {
  fs::path p = statement_file;
  return p.replace_extension(".last-error.txt");
}

OutboxEntry entry_of(const fs::path& file, bool rejected) {
  OutboxEntry e;
  e.file = file;
  e.statement_id = file.stem().string();
  e.rejected = rejected;
  const auto json = nlohmann::json::parse(read_text(file), nullptr, false);
  if (json.is_object()) {
    if (json.contains("actor") && json["actor"].contains("account"))
      e.actor = json["actor"]["account"].value("name", std::string());
    e.timestamp = json.value("timestamp", std::string());
  }
  fs::path reason = rejected ? fs::path(file).replace_extension(".reason.txt") : error_file_of(file);
  if (fs::exists(reason)) e.last_error = read_text(reason);
  return e;
}

std::vector<fs::path> statement_files(const fs::path& folder) {
  std::vector<fs::path> files;
  std::error_code error;
  for (const auto& item : fs::directory_iterator(folder, error)) {
    const auto& p = item.path();
    if (item.is_regular_file() && p.extension() == ".json") files.push_back(p);
  }
  // Oldest first, so statements reach the LRS in the order they were made.
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    std::error_code e;
    const auto ta = fs::last_write_time(a, e), tb = fs::last_write_time(b, e);
    return ta != tb ? ta < tb : a < b;
  });
  return files;
}

}  // namespace

StatementOutbox::StatementOutbox(fs::path folder) : folder_(std::move(folder)) {
  std::error_code error;
  fs::create_directories(folder_, error);
  if (error || !fs::is_directory(folder_))
    throw std::runtime_error(fmt::format("{}: cannot create the xAPI outbox folder", folder_.string()));
}

fs::path StatementOutbox::add(const nlohmann::json& statement) {
  const fs::path file = folder_ / (file_stem_for(statement) + ".json");
  write_atomically(file, statement.dump(2) + "\n");
  std::error_code error;
  fs::remove(error_file_of(file), error);
  return file;
}

std::vector<OutboxEntry> StatementOutbox::list() const {
  std::vector<OutboxEntry> entries;
  for (const auto& f : statement_files(folder_)) entries.push_back(entry_of(f, false));
  for (const auto& f : statement_files(folder_ / "rejected")) entries.push_back(entry_of(f, true));
  return entries;
}

void StatementOutbox::record_failure(const fs::path& file, const SendResult& result) const {
  write_atomically(error_file_of(file), result.reason + "\n");
}

void StatementOutbox::reject(const fs::path& file, const SendResult& result) const {
  const fs::path aside = folder_ / "rejected";
  fs::create_directories(aside);
  write_atomically(aside / (file.stem().string() + ".reason.txt"), result.reason + "\n");
  fs::rename(file, aside / file.filename());
  std::error_code error;
  fs::remove(error_file_of(file), error);
}

FlushReport StatementOutbox::flush(const Sender& send) {
  FlushReport report;
  const auto files = statement_files(folder_);
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto statement = nlohmann::json::parse(read_text(files[i]), nullptr, false);
    if (statement.is_discarded()) {
      reject(files[i], {Delivery::Rejected, 0, "not JSON (damaged outbox file)"});
      ++report.rejected;
      continue;
    }
    const SendResult result = send(statement);
    if (result.delivery == Delivery::Stored) {
      std::error_code error;
      fs::remove(files[i], error);
      fs::remove(error_file_of(files[i]), error);
      ++report.stored;
      continue;
    }
    report.last_reason = result.reason;
    if (result.delivery == Delivery::Rejected) {
      reject(files[i], result);
      ++report.rejected;
      continue;
    }
    record_failure(files[i], result);
    report.waiting = static_cast<int>(files.size() - i);  // the LRS is down: keep the rest for later
    break;
  }
  return report;
}

FlushReport deliver(StatementOutbox& outbox, const std::string& endpoint, int attempts, double timeout_s) {
  const Sender send = [&endpoint, timeout_s](const nlohmann::json& s) { return put_statement(endpoint, s, timeout_s); };
  FlushReport total;
  double wait_s = 0.5;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    if (attempt > 0) {
      std::this_thread::sleep_for(std::chrono::duration<double>(wait_s));
      wait_s *= 2.0;
    }
    const FlushReport r = outbox.flush(send);
    total.stored += r.stored;
    total.rejected += r.rejected;
    total.waiting = r.waiting;
    if (!r.last_reason.empty()) total.last_reason = r.last_reason;
    if (r.waiting == 0) break;
  }
  return total;
}

fs::path default_outbox_folder() {
  if (const char* data = std::getenv("XDG_DATA_HOME"); data && *data) return fs::path(data) / "palpa" / "xapi-outbox";
  const char* home = std::getenv("HOME");
  return fs::path(home && *home ? home : ".") / ".local" / "share" / "palpa" / "xapi-outbox";
}

}  // namespace palpa::lrs

#include "palpa/report/session_header.hpp"

#include "palpa/report/encoding.hpp"

namespace palpa::report {

SessionHeader header_of(const session::SessionInfo& info, const std::filesystem::path& file) {
  SessionHeader h;
  h.id = info.id;
  h.trainee = info.trainee;
  const auto title = info.case_document.is_object() ? info.case_document.find("title") : info.case_document.end();
  if (info.case_document.is_object() && title != info.case_document.end() && title->is_string())
    h.case_title = title->get<std::string>();
  h.case_source = info.case_source;
  h.device = info.device;
  h.software_version = info.software_version;
  h.started_at = info.started_at;
  h.file = file.string();
  h.mode = session::session_mode(info);
  h.case_file = std::filesystem::path(info.case_source).filename().string();
  h.case_id = case_activity_id(h);
  if (info.extra.is_object() && info.extra.contains("station") && info.extra["station"].is_string())
    h.station = info.extra["station"].get<std::string>();
  return h;
}

nlohmann::json to_json(const SessionHeader& h) {
  return {{"id", h.id},
          {"trainee", h.trainee},
          {"case", h.case_title},
          {"case_source", h.case_source},
          {"device", h.device},
          {"software_version", h.software_version},
          {"started_at", h.started_at},
          {"file", h.file},
          {"mode", h.mode},
          {"case_file", h.case_file},
          {"case_id", h.case_id},
          {"station", h.station}};
}

std::string slug(std::string_view text) {
  std::string out;
  bool dash = false;
  for (const char c : text) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    const bool upper = c >= 'A' && c <= 'Z';
    if (alnum || upper) {
      if (dash && !out.empty()) out += '-';
      dash = false;
      out += upper ? static_cast<char>(c - 'A' + 'a') : c;
      if (out.size() >= 64) break;
    } else {
      dash = true;
    }
  }
  return out;
}

std::string case_activity_id(const SessionHeader& h) {
  std::string key = slug(h.case_title);
  if (key.empty() && h.case_title.empty()) key = slug(std::filesystem::path(h.case_source).stem().string());
  if (key.empty()) {
    static constexpr char kHex[] = "0123456789abcdef";
    const auto digest = sha1(h.case_title);
    key = "sha1-";
    for (std::size_t i = 0; i < 6; ++i) {
      key += kHex[digest[i] >> 4];
      key += kHex[digest[i] & 15];
    }
  }
  return "urn:palpa:case:" + key;
}

std::string case_name(const SessionHeader& h) {
  if (!h.case_title.empty()) return h.case_title;
  const auto name = std::filesystem::path(h.case_source).filename().string();
  return name.empty() ? std::string("(untitled case)") : name;
}

}  // namespace palpa::report

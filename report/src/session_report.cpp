#include "palpa/report/session_report.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>

#include "palpa/report/force_trace.hpp"
#include "palpa/report/report_json.hpp"
#include "palpa/report/session_html.hpp"
#include "palpa/report/summary_csv.hpp"
#include "palpa/report/xapi.hpp"

namespace palpa::report {

void write_text(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (out) out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (out) out.close();
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

std::vector<std::filesystem::path> session_report_paths(const std::filesystem::path& dir, const std::string& stem,
                                                        const ReportFiles& files) {
  std::vector<std::filesystem::path> paths;
  if (files.json) paths.push_back(dir / (stem + ".json"));
  if (files.xapi) paths.push_back(dir / (stem + ".xapi.json"));
  if (files.csv) paths.push_back(dir / (stem + ".csv"));
  if (files.html) paths.push_back(dir / (stem + ".html"));
  return paths;
}

void write_session_report(const std::filesystem::path& dir, const std::string& stem, const SessionHeader& header,
                          const session::Session& session, const score::Score& score, const ReportFiles& files) {
  ForceTrace trace(session, session.samples.size());
  trace.add(session.samples);
  trace.finish();
  write_session_report(dir, stem, header, trace, score, files);
}

void write_session_report(const std::filesystem::path& dir, const std::string& stem, const SessionHeader& header,
                          const ForceTrace& trace, const score::Score& score, const ReportFiles& files) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create the folder: " + ec.message());
  if (files.json) write_text(dir / (stem + ".json"), report_json(header, score).dump(2) + "\n");
  if (files.xapi) write_text(dir / (stem + ".xapi.json"), xapi_statement(header, score, files.xapi_home_page).dump(2) + "\n");
  if (files.csv) write_text(dir / (stem + ".csv"), csv_header() + "\n" + csv_row(header, score) + "\n");
  if (files.html) write_text(dir / (stem + ".html"), session_html(header, score, render_images(trace, score)));
}

}  // namespace palpa::report

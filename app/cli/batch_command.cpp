// palpa-cli batch PATH... --out DIR [--jobs N] [--reports]: scores many sessions in a pool
// of threads and writes a summary CSV, each trainee's learning curve (CSV, PNG, CUSUM of
// failures) and a cohort page. Unreadable sessions are reported and skipped.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "batch_store.hpp"
#include "commands.hpp"
#include "output_guard.hpp"
#include "palpa/options/number_checks.hpp"
#include "palpa/report/cohort.hpp"
#include "palpa/report/cohort_tables.hpp"
#include "palpa/report/encoding.hpp"
#include "palpa/report/force_trace.hpp"
#include "palpa/report/images.hpp"
#include "palpa/report/learning_curve.hpp"
#include "palpa/report/proficiency.hpp"
#include "palpa/report/session_filter.hpp"
#include "palpa/report/session_report.hpp"
#include "palpa/report/summary_csv.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session_reader.hpp"

namespace palpa::cli {
namespace {

namespace fs = std::filesystem;

struct BatchOptions {
  std::vector<std::string> paths;
  std::string out;
  int jobs = 0;  ///< 0: all cores
  bool reports = false;
  bool include_abandoned = false;  ///< learning curves: also the attempts a trainee abandoned
  bool all_modes = false;          ///< learning curves: every mode, not trainee exercises only
  bool force = false;              ///< the outputs of an earlier batch in --out may be replaced
  report::SessionFilter filter;    ///< --since/--until/--case/--trainee: which sessions the outputs cover
  StoreBatchOptions store;         ///< --store: against the centre store (batch_store.cpp)
  /// --store --out: the station each downloaded file was pushed from (the store's word, not
  /// the file's extra.station), and the stored sessions that could not be written.
  std::map<std::string, std::string> station_of;
  std::map<std::string, StoredRow> row_of;  ///< --store --out: each file's row, which it must agree with
  std::map<std::string, std::string> result_of;  ///< --store --out: the worker's stored score of each file
  std::vector<report::SkippedFile> not_downloaded;
  std::vector<std::string> pending;  ///< --store --out: sessions no worker has scored yet
};


struct Input {
  std::string file;  ///< as found (the given spelling, or folder / relative path)
  std::string stem;  ///< unique among the inputs: names the per-session report files
  std::string error; ///< set when the path could not even be listed
};

// Why the batch may not write into `out`: an earlier batch's outputs are there (without
// --force), or an input is one of the files it writes; empty when it may.
std::string out_refusal(const fs::path& out, bool force, const std::vector<Input>& inputs) {
  std::vector<fs::path> files;
  for (const auto& input : inputs) files.emplace_back(input.file);
  std::vector<fs::path> outputs{out / "summary.csv", out / "errors.csv", out / "cohort.html", out / "cases.csv",
                                 out / "stations.csv"};
  std::error_code ec;
  for (const char* folder : {"trainees", "sessions"}) {
    for (fs::directory_iterator it(out / folder, ec), end; !ec && it != end; it.increment(ec)) {
      outputs.push_back(it->path());
    }
    ec.clear();
  }
  // curves/TRAINEE/CASE.csv and .png: the files, not their folders
  for (fs::recursive_directory_iterator it(out / "curves", ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code type_ec;
    if (!it->is_directory(type_ec)) outputs.push_back(it->path());
  }
  return refusal_to_write(outputs, force, files);
}

/// One scored session as kept until the end: no samples, no maps.
struct Scored {
  report::SessionHeader header;
  score::Score score;
  std::string stem;  ///< Input::stem: names its report files under sessions/
};

struct Outcome {
  std::optional<Scored> scored;
  std::string error;          ///< one line when skipped
  bool left_out = false;      ///< read, but outside the filter: neither scored nor reported
};

/// Explicit files whatever their extension; folders searched recursively for *.palpa.
/// De-duplicated by canonical path, sorted by name so runs are reproducible.
std::vector<Input> collect_inputs(const std::vector<std::string>& paths) {
  std::map<std::string, Input> by_key;  // canonical path -> input
  auto add = [&by_key](const fs::path& p, std::string error = {}) {
    std::error_code ec;
    auto key = fs::weakly_canonical(p, ec).string();
    if (ec) key = p.lexically_normal().string();
    by_key.try_emplace(key, Input{p.string(), {}, std::move(error)});
  };
  for (const auto& given : paths) {
    const fs::path p(given);
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> found;
      fs::recursive_directory_iterator it(p, fs::directory_options::skip_permission_denied, ec), end;
      for (; !ec && it != end; it.increment(ec)) {
        std::error_code type_ec;
        if (it->path().extension() == ".palpa" && it->is_regular_file(type_ec)) found.push_back(it->path());
      }
      if (ec) add(p, given + ": folder: cannot be listed: " + ec.message());
      for (const auto& f : found) add(f);
    } else if (fs::exists(p, ec)) {
      add(p);
    } else {
      add(p, given + ": file: does not exist");
    }
  }
  std::vector<Input> inputs;
  for (auto& [key, input] : by_key) inputs.push_back(std::move(input));
  std::sort(inputs.begin(), inputs.end(), [](const Input& a, const Input& b) { return a.file < b.file; });
  // Report stems: the file's stem, numbered when two files share it.
  std::map<std::string, int> seen;
  for (auto& input : inputs) {
    std::string stem = fs::path(input.file).stem().string();
    if (stem.empty()) stem = "session";
    const int n = ++seen[stem];
    if (n > 1) stem = fmt::format("{}-{}", stem, n);
    input.stem = stem;
  }
  return inputs;
}

/// Progress on stderr: a bar redrawn in place on a terminal, nothing otherwise. Error lines
/// go through it so they do not tear the bar.
class Progress {
 public:
  explicit Progress(std::size_t total) : total_(total), tty_(isatty(STDERR_FILENO) == 1) {}
  void error(const std::string& message) {
    std::lock_guard lock(mutex_);
    if (tty_) std::fputs("\r\033[K", stderr);
    print_error(message);
    draw();
  }
  void done() {
    std::lock_guard lock(mutex_);
    ++done_;
    draw();
  }
  void finish() {
    std::lock_guard lock(mutex_);
    if (tty_) std::fputs("\r\033[K", stderr);
  }

 private:
  void draw() {
    if (!tty_ || total_ == 0) return;
    constexpr std::size_t kWidth = 40;
    const std::size_t filled = done_ * kWidth / total_;
    std::fprintf(stderr, "\r[%s%s] %zu/%zu sessions", std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, ' ').c_str(), done_, total_);
    std::fflush(stderr);
  }
  std::mutex mutex_;
  std::size_t total_, done_ = 0;
  bool tty_;
};

std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

/// A downloaded file must say what its row in the store says (the row passed the server's
/// checks; the file did not): throws SessionError naming the first field that differs.
void check_row(const session::Session& head, const StoredRow& row, const std::string& file) {
  const char* field = head.info.id != row.session_id                   ? "id"
                      : head.info.trainee != row.trainee               ? "trainee"
                      : session::session_mode(head.info) != row.mode ? "mode"
                                                                       : nullptr;
  if (field != nullptr) {
    throw session::SessionError(file, "meta", fmt::format("the file's {} differs from the store's row; not reported",
                                                          field));
  }
}

/// The score a worker stored for a file from the store (its figures as the worker found
/// them, the thresholds from the file's case), or the file scored here.
score::Score stored_or_scored(session::SampleStream& stream, const std::string& file, const BatchOptions& o) {
  const auto it = o.result_of.find(file);
  if (it == o.result_of.end()) return score::score_stream(stream, file);
  const auto json = nlohmann::json::parse(it->second, nullptr, false);
  std::vector<io::Problem> problems;
  const auto thresholds = score::thresholds_from_case(stream.head().info.case_document, problems);
  try {
    if (json.is_discarded() || !problems.empty()) throw std::invalid_argument("stored score: not readable");
    return score::score_from_json(json, thresholds);
  } catch (const std::invalid_argument& e) {
    throw session::SessionError(file, "score", std::string(e.what()) + "; not reported");
  }
}

/// A stored session's page draws its force plot from a pass over every sample, made in
/// this process: past kMaxStoredTraceTicks (20 minutes at 1 kHz) it is left out, with a note,
/// so that a station's long files cost a report no more than honest ones (docs/centre.md).
constexpr std::uint64_t kMaxStoredTraceTicks = 1'200'000;

std::unique_ptr<report::ForceTrace> trace_for_page(const session::SampleStream& stream, const std::string& file,
                                                   const BatchOptions& o, score::Score& score) {
  if (!o.result_of.contains(file) || stream.declared_count() <= kMaxStoredTraceTicks) {
    return report::read_force_trace(file);
  }
  score.notes.push_back(fmt::format("force plot not drawn: {} samples, more than a report from the store reads "
                                    "({}); palpa-cli score FILE --report DIR draws it",
                                    stream.declared_count(), kMaxStoredTraceTicks));
  auto empty = std::make_unique<report::ForceTrace>(stream.head(), 0);
  empty->finish();
  return empty;
}

/// Reads and scores one session (and writes its report files); the samples are dropped on return.
Outcome process(const Input& input, const fs::path& sessions_dir, const BatchOptions& o, std::string& output_error) {
  Outcome outcome;
  if (!input.error.empty()) {
    outcome.error = input.error;
    return outcome;
  }
  try {
    // The samples as a stream: memory that of the case, however long the session.
    session::SampleStream stream(input.file);
    auto header = report::header_of(stream.head().info, input.file);
    if (const auto it = o.station_of.find(input.file); it != o.station_of.end()) header.station = it->second;
    if (const auto it = o.row_of.find(input.file); it != o.row_of.end()) check_row(stream.head(), it->second, input.file);
    if (!o.filter.matches(header)) {
      // Read through all the same: a damaged file is reported whatever the filter. Not a
      // file from the store: a worker read it whole, and this process reads only heads.
      if (!o.result_of.contains(input.file)) {
        while (!stream.next().empty()) {
        }
      }
      outcome.left_out = true;
      return outcome;
    }
    auto score = stored_or_scored(stream, input.file, o);
    if (o.reports) {
      try {  // the force plot's trace from a second pass: no sample is kept
        report::write_session_report(sessions_dir, input.stem, header, *trace_for_page(stream, input.file, o, score),
                                     score, {true, true, true, false});
      } catch (const std::exception& e) {
        output_error = e.what();
      }
    }
    score.maps.clear();  // the batch keeps only what its tables need
    score.maps.shrink_to_fit();
    outcome.scored = Scored{std::move(header), std::move(score), input.stem};
  } catch (const session::SessionError& e) {
    outcome.error = one_line(e.what());
  } catch (const std::exception& e) {
    outcome.error = one_line(input.file + ": score: " + e.what());
  }
  return outcome;
}

// The pool: each worker takes the next file, reads and scores it, keeps the summary.
// Returns the outcomes in input order; `output_failure` gets the first report-writing error.
std::vector<Outcome> score_all(const std::vector<Input>& inputs, const BatchOptions& o, const fs::path& out,
                               std::string& output_failure) {
  std::vector<Outcome> outcomes(inputs.size());
  std::atomic<std::size_t> next{0};
  std::mutex output_mutex;
  Progress progress(inputs.size());
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t jobs =
      std::clamp<std::size_t>(o.jobs > 0 ? static_cast<std::size_t>(o.jobs) : cores, 1, std::max<std::size_t>(1, inputs.size()));
  auto work = [&] {
    for (std::size_t i = next++; i < inputs.size(); i = next++) {
      std::string output_error;
      outcomes[i] = process(inputs[i], out / "sessions", o, output_error);
      if (!output_error.empty()) {
        std::lock_guard lock(output_mutex);
        if (output_failure.empty()) output_failure = output_error;
      }
      if (!outcomes[i].error.empty()) progress.error(outcomes[i].error);
      progress.done();
    }
  };
  {
    std::vector<std::jthread> pool;
    for (std::size_t k = 1; k < jobs; ++k) pool.emplace_back(work);
    work();
  }
  progress.finish();
  return outcomes;
}

void write_summary(const fs::path& out, const std::vector<Scored>& scored,
                   const std::vector<report::SkippedFile>& skipped) {
  std::string summary = report::csv_header() + "\n";
  for (const auto& s : scored) summary += report::csv_row(s.header, s.score) + "\n";
  report::write_text(out / "summary.csv", summary);
  std::string errors = "file,error\n";
  for (const auto& s : skipped) errors += report::csv_text(s.file) + "," + report::csv_text(s.error) + "\n";
  report::write_text(out / "errors.csv", errors);
}

// A learning curve from attempts in order: CSV and PNG at `files` (relative to out, no
// extension). Per-case curves keep no PNG in memory: the page links to their files.
report::TraineeCurve write_curve(const fs::path& out, const std::vector<const Scored*>& attempts,
                                 const std::string& files, bool keep_png) {
  report::TraineeCurve curve;
  curve.trainee = attempts.front()->header.trainee;
  curve.file_stem = report::trainee_file_stem(curve.trainee);
  curve.files = files;
  std::vector<bool> passed;
  for (const Scored* a : attempts) {
    curve.attempts.push_back(report::attempt_of(a->header, a->score));
    passed.push_back(a->score.passed);
  }
  curve.cusum = report::failure_cusum(passed);
  curve.proficiency = report::proficiency(passed);
  report::write_text(out / (files + ".csv"), report::trainee_csv(curve.attempts, curve.cusum, curve.proficiency));
  curve.png =
      report::png_bytes(report::learning_curve_plot(curve.trainee, curve.attempts, curve.cusum, curve.proficiency));
  report::write_text(out / (files + ".png"),
                     std::string_view(reinterpret_cast<const char*>(curve.png.data()), curve.png.size()));
  if (!keep_png) curve.png = {};
  return curve;
}

// Learning curves follow a trainee's exams: by default trainee exercises only, and no
// attempt the trainee abandoned (summary.csv still lists every session); the others are
// tallied in `left_out` for the page's notes. `scored` is sorted by trainee then start.
std::vector<const Scored*> curve_attempts(const std::vector<Scored>& scored, const BatchOptions& o,
                                          report::LeftOut& left_out) {
  // A session counts when its station is enrolled for the trainee by a coordinator, or by
  // its own first push while no coordinator enrolled the trainee and no other station
  // pushed for them. Pushed from elsewhere too, a first push proves nothing (whoever
  // pushed first may be the intruder): the trainee is disputed until a coordinator says.
  std::set<std::string> pushed_elsewhere;
  for (const auto& [file, row] : o.row_of) {
    if (!row.enrolled) pushed_elsewhere.insert(row.trainee);
  }
  const auto not_enrolled = [](const StoredRow& r) { return !r.enrolled || (r.provisional && r.trainee_confirmed); };
  std::vector<const Scored*> attempts;
  for (const auto& s : scored) {
    const auto row = o.row_of.find(s.header.file);
    const bool stored = row != o.row_of.end();
    if (stored && !not_enrolled(row->second) && row->second.provisional &&
        pushed_elsewhere.contains(s.header.trainee)) {
      left_out.disputed[s.header.trainee].insert(s.header.station);
    } else if (stored && not_enrolled(row->second)) {
      left_out.unenrolled[s.header.trainee].insert(s.header.station);
      ++left_out.unenrolled_sessions;
    } else if (s.header.mode != "trainee" && !o.all_modes) {
      ++left_out.by_mode[s.header.mode];
    } else if (s.score.abandoned && !o.include_abandoned) {
      ++left_out.abandoned;
    } else {
      attempts.push_back(&s);
    }
  }
  for (auto& [trainee, stations] : left_out.disputed) {
    if (const auto other = left_out.unenrolled.find(trainee); other != left_out.unenrolled.end()) {
      stations.insert(other->second.begin(), other->second.end());
    }
  }
  return attempts;
}

// One curve per trainee over every case: trainees/STEM.csv and .png, as tools expect them.
std::vector<report::TraineeCurve> write_trainee_curves(const fs::path& out,
                                                       const std::vector<const Scored*>& attempts) {
  std::vector<report::TraineeCurve> curves;
  for (std::size_t begin = 0; begin < attempts.size();) {
    std::size_t end = begin;
    while (end < attempts.size() && attempts[end]->header.trainee == attempts[begin]->header.trainee) ++end;
    const auto stem = report::trainee_file_stem(attempts[begin]->header.trainee);
    curves.push_back(write_curve(out, {attempts.begin() + static_cast<std::ptrdiff_t>(begin),
                                       attempts.begin() + static_cast<std::ptrdiff_t>(end)},
                                 "trainees/" + stem, true));
    begin = end;
  }
  return curves;
}

// One curve per trainee and case, so that cases of different difficulty are not mixed:
// curves/TRAINEE_STEM/CASE_STEM.csv and .png (a folder per trainee: no stem can be split
// two ways).
std::vector<report::TraineeCurve> write_case_curves(const fs::path& out, const std::vector<const Scored*>& attempts) {
  std::map<std::pair<std::string, std::string>, std::vector<const Scored*>> by_pair;  // keeps start order
  for (const Scored* a : attempts) by_pair[{a->header.trainee, a->header.case_id}].push_back(a);
  std::vector<report::TraineeCurve> curves;
  for (const auto& [key, pair_attempts] : by_pair) {
    const auto folder = "curves/" + report::trainee_file_stem(key.first);
    fs::create_directories(out / folder);
    auto curve = write_curve(out, pair_attempts, folder + "/" + report::case_file_stem(key.second), false);
    curve.case_id = key.second;
    curve.case_name = report::case_name(pair_attempts.front()->header);
    curves.push_back(std::move(curve));
  }
  return curves;
}

// The options that made the filter, for the note on what it left out: "--since, --case".
std::string filter_options(const report::SessionFilter& f) {
  std::string names;
  for (const auto& [value, name] : {std::pair{&f.since, "--since"}, std::pair{&f.until, "--until"},
                                    std::pair{&f.case_key, "--case"}, std::pair{&f.trainee, "--trainee"}}) {
    if (!value->empty()) names += (names.empty() ? "" : ", ") + std::string(name);
  }
  return names;
}

// cases.csv and stations.csv: every scored session, whatever its mode, as summary.csv.
void write_group_summaries(const fs::path& out, const std::vector<Scored>& scored, report::CohortPage& page) {
  std::vector<report::SessionFacts> facts;
  for (const auto& s : scored) facts.push_back({&s.header, s.score.score, s.score.passed, s.score.abandoned});
  report::ProficientPairs proficient;
  for (const auto& c : page.case_curves) {
    if (c.proficiency.now()) proficient.insert({c.trainee, c.case_id});
  }
  page.cases = report::case_summaries(facts, proficient);
  page.stations = report::station_summaries(facts, proficient);
  report::write_text(out / "cases.csv", report::cases_csv(page.cases));
  report::write_text(out / "stations.csv", report::stations_csv(page.stations));
}

// With --reports: each session's page, linked from the cohort page by its (file-name) stem.
std::vector<report::SessionLink> session_links(const std::vector<Scored>& scored) {
  std::vector<report::SessionLink> links;
  for (const auto& s : scored) {
    links.push_back({s.header.trainee, s.header.started_at, report::outcome_of(s.score),
                     report::relative_href("sessions", s.stem, ".html")});
  }
  return links;
}

// The learning curves, the summaries and the cohort page; the page's notes (what the
// curves leave out, and the option that includes it) also go to stderr.
void write_cohort(const fs::path& out, const std::vector<Scored>& scored,
                  const std::vector<report::SkippedFile>& skipped, const BatchOptions& o, std::size_t filtered) {
  report::LeftOut left_out;
  left_out.filtered = filtered;
  left_out.filter = o.filter.describe();
  left_out.filter_options = filter_options(o.filter);
  const auto attempts = curve_attempts(scored, o, left_out);
  report::CohortPage page;
  page.trainees = write_trainee_curves(out, attempts);
  page.case_curves = write_case_curves(out, attempts);
  write_group_summaries(out, scored, page);
  if (o.reports) page.sessions = session_links(scored);
  page.skipped = skipped;
  page.selection = o.filter.describe();
  page.notes = report::left_out_notes(left_out);
  std::map<std::string, std::set<std::string>> stations;
  for (const Scored* a : attempts) stations[a->header.trainee].insert(a->header.station);
  for (auto& note : report::several_station_notes(stations)) page.notes.push_back(std::move(note));
  if (!o.pending.empty()) {
    page.notes.push_back(fmt::format("{} stored session{} not scored by a worker yet (pending): not in this report; "
                                     "they are scored by palpa-cli batch --store URL --worker",
                                     o.pending.size(), o.pending.size() == 1 ? " is" : "s are"));
  }
  report::write_text(out / "cohort.html", report::cohort_html(page));
  for (const auto& note : page.notes) std::fprintf(stderr, "batch: %s\n", note.c_str());
}

int run_batch(const BatchOptions& o) {
  try {
    o.filter.validate();
  } catch (const report::FilterError& e) {
    print_error(e.what());
    return kBadInput;
  }
  const auto inputs = collect_inputs(o.paths);
  const fs::path out(o.out);
  if (auto why = out_refusal(out, o.force, inputs); !why.empty()) {
    print_error("--out: " + why);
    return kBadInput;
  }
  std::error_code ec;
  fs::create_directories(out / "trainees", ec);
  if (!ec && o.reports) fs::create_directories(out / "sessions", ec);
  if (ec) {
    print_error(o.out + ": cannot create the output folder: " + ec.message());
    return kFailure;
  }
  std::string output_failure;
  std::vector<Outcome> outcomes = score_all(inputs, o, out, output_failure);

  std::vector<Scored> scored;
  std::vector<report::SkippedFile> skipped = o.not_downloaded;
  std::size_t left_out = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (outcomes[i].left_out) {
      ++left_out;
    } else if (outcomes[i].scored) {
      scored.push_back(std::move(*outcomes[i].scored));
    } else {
      skipped.push_back({inputs[i].file, outcomes[i].error});
    }
  }
  std::sort(scored.begin(), scored.end(), [](const Scored& a, const Scored& b) {
    return std::tie(a.header.trainee, a.header.started_at, a.header.file) <
           std::tie(b.header.trainee, b.header.started_at, b.header.file);
  });
  try {
    write_summary(out, scored, skipped);
    write_cohort(out, scored, skipped, o, left_out);
  } catch (const std::exception& e) {
    print_error(e.what());
    return kFailure;
  }
  if (!output_failure.empty()) {
    print_error(output_failure);
    return kFailure;
  }
  const std::string filtered =
      o.filter.empty() ? std::string() : fmt::format(", {} outside {}", left_out, o.filter.describe());
  std::fprintf(stderr, "batch: %zu of %zu sessions scored, %zu skipped%s; wrote %s\n", scored.size(), inputs.size(),
               skipped.size(), filtered.c_str(), (out / "summary.csv").c_str());
  if (inputs.empty() && o.store.store.empty()) {
    print_error("no session files found (folders are searched for *.palpa)");
    return kBadInput;
  }
  if (scored.empty()) {  // every empty selection alike: nothing found, or nothing matched the filter
    print_error(o.filter.empty() ? "no session could be scored" : "no session is " + o.filter.describe());
    return kBadInput;
  }
  return skipped.empty() ? kOk : kBadInput;
}

}  // namespace

Command add_batch_command(CLI::App& parent) {
  auto o = std::make_shared<BatchOptions>();
  auto* app = parent.add_subcommand(
      "batch", "Score many sessions: PATHs are session files (any extension) or folders searched recursively for "
               "*.palpa. Writes DIR/summary.csv (one row per session, by trainee then start time), DIR/errors.csv "
               "(skipped files), DIR/cases.csv and DIR/stations.csv (per case and per station), "
               "DIR/trainees/TRAINEE.csv and .png (learning curve with a CUSUM of failures), the same per case "
               "under DIR/curves/TRAINEE/CASE.csv and .png, and DIR/cohort.html. Exit 0 when every session was scored, 2 when any was skipped (the outputs are "
               "still written), 1 when an output could not be written.");
  app->add_option("PATH", o->paths, "session files or folders (required unless --store)");
  app->add_option("--out", o->out,
                  "output folder (created if needed); the outputs of an earlier batch there are replaced only with "
                  "--force, and never a session given as input (required unless --store --worker)");
  app->add_flag("--force", o->force, "replace the outputs of an earlier batch in --out");
  app->add_option("--jobs", o->jobs, "worker threads; default: all cores")->check(options::integer_in(1, 1024));
  app->add_flag("--reports", o->reports, "also write DIR/sessions/STEM.html, STEM.json and STEM.xapi.json per session");
  app->add_flag("--include-abandoned", o->include_abandoned,
                "learning curves also count attempts the trainee abandoned (summary.csv always lists them)");
  app->add_flag("--all-modes", o->all_modes,
                "learning curves count every session (scripted, replays, instructors' Try it), not trainee "
                "exercises only");
  app->add_option("--since", o->filter.since,
                  "only sessions started on or after DATE (YYYY-MM-DD, or a time such as 2026-11-01T08:00:00Z)");
  app->add_option("--until", o->filter.until, "only sessions started on or before DATE (a date: up to its end)");
  app->add_option("--case", o->filter.case_key,
                  "only sessions of this case: its case_id or case_file as in summary.csv (or without "
                  "urn:palpa:case: / .json)");
  app->add_option("--trainee", o->filter.trainee, "only this trainee's sessions");
  add_store_batch_options(app, o->store);
  return {app, [o] {
            if (!o->store.store.empty()) {
              o->store.jobs = o->jobs;
              o->store.filter = o->filter;
              return run_store_batch(o->store, o->out, [o](const StoreDownload& d) {
                auto folder = *o;
                folder.paths = d.files;
                folder.station_of = d.station_of;
                folder.row_of = d.row_of;
                folder.result_of = d.result_of;
                folder.pending = d.pending;
                folder.not_downloaded = d.skipped;
                return run_batch(folder);
              });
            }
            if (o->paths.empty() || o->out.empty()) {
              print_error(o->paths.empty() ? "batch: PATH is required (or --store)" : "batch: --out is required");
              return static_cast<int>(kBadInput);
            }
            return run_batch(*o);
          }};
}

}  // namespace palpa::cli

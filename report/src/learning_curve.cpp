#include "palpa/report/learning_curve.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "palpa/plot/line_plot.hpp"
#include "palpa/report/csv_number.hpp"
#include "palpa/report/encoding.hpp"
#include "palpa/report/summary_csv.hpp"

namespace palpa::report {

double CusumDesign::s() const {
  const double p = std::log(p1 / p0), q = std::log((1.0 - p0) / (1.0 - p1));
  return q / (p + q);
}
double CusumDesign::h0() const {
  const double p = std::log(p1 / p0), q = std::log((1.0 - p0) / (1.0 - p1));
  return std::log((1.0 - alpha) / beta) / (p + q);
}
double CusumDesign::h1() const {
  const double p = std::log(p1 / p0), q = std::log((1.0 - p0) / (1.0 - p1));
  return std::log((1.0 - beta) / alpha) / (p + q);
}

std::string_view to_string(CusumSignal signal, std::string_view none_text) {
  switch (signal) {
    case CusumSignal::Acceptable: return "acceptable";
    case CusumSignal::Unacceptable: return "unacceptable";
    default: return none_text;
  }
}

Cusum failure_cusum(const std::vector<bool>& passed, const CusumDesign& design) {
  const double s = design.s(), h0 = design.h0(), h1 = design.h1();
  // A tiny tolerance so that a sum of steps landing on a limit in exact arithmetic signals.
  constexpr double kEps = 1e-9;
  Cusum c;
  double value = 0.0;
  for (const bool ok : passed) {
    value += ok ? -s : 1.0 - s;
    CusumSignal signal = CusumSignal::None;
    if (value >= h1 - kEps) {
      signal = CusumSignal::Unacceptable;
    } else if (-value >= h0 - kEps) {
      signal = CusumSignal::Acceptable;
    }
    c.value.push_back(value);
    c.signal.push_back(signal);
    if (signal != CusumSignal::None) {
      c.verdict = signal;
      value = 0.0;  // the next attempt starts a new test
    }
  }
  return c;
}

std::string cusum_caption(const CusumDesign& d) {
  return fmt::format(
      "Each failure raises the line by {:.2f}, each pass lowers it by {:.2f}; touching the upper line ({:.2f}) "
      "means the failure rate is probably above {:.0f} %, touching the lower line ({:.2f}) that it is probably "
      "below {:.0f} % (each wrong about {:.0f} times in 100); the line then restarts at 0.",
      1.0 - d.s(), d.s(), d.h1(), 100.0 * d.p1, -d.h0(), 100.0 * d.p0, 100.0 * std::max(d.alpha, d.beta));
}

std::string cusum_words(const Cusum& cusum, const CusumDesign& d) {
  for (std::size_t i = cusum.signal.size(); i-- > 0;) {
    if (cusum.signal[i] == CusumSignal::Unacceptable)
      return fmt::format("failure rate probably above {:.0f} % (attempt {})", 100.0 * d.p1, i + 1);
    if (cusum.signal[i] == CusumSignal::Acceptable)
      return fmt::format("failure rate probably below {:.0f} % (attempt {})", 100.0 * d.p0, i + 1);
  }
  return "no signal yet";
}

Attempt attempt_of(const SessionHeader& header, const score::Score& score) {
  return {header, score.score, score.passed, score.sensitivity, score.coverage, score.deep_coverage};
}

std::string trainee_csv(const std::vector<Attempt>& attempts, const Cusum& cusum, const Proficiency& proficiency) {
  std::string csv =
      "attempt,started_at,file,session_id,score,passed,sensitivity,coverage,deep_coverage,cusum,signal,"
      "score_100,proficient,verdict,station\n";
  auto share = [](double v) { return csv_number(v, CsvUnit::Fraction); };
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    const auto& a = attempts[i];
    csv += fmt::format("{},{},{},{},{},{},{},{},{},", i + 1, csv_text(a.header.started_at), csv_text(a.header.file),
                       csv_text(a.header.id), share(a.score), a.passed ? "1" : "0", share(a.sensitivity),
                       share(a.coverage), share(a.deep_coverage));
    csv += fmt::format("{},{},{},{},{},{}\n", i < cusum.value.size() ? csv_number(cusum.value[i], CsvUnit::Cusum) : "",
                       i < cusum.signal.size() ? to_string(cusum.signal[i]) : std::string_view(),
                       csv_number(100.0 * a.score, CsvUnit::Score100),
                       i < proficiency.proficient.size() ? (proficiency.proficient[i] ? "1" : "0") : "",
                       i < proficiency.verdict.size() ? csv_text(proficiency.verdict[i]) : std::string(),
                       csv_text(a.header.station));
  }
  return csv;
}

namespace {

std::string ascii(std::string_view text) {  // Hershey fonts: printable ASCII only
  std::string out;
  for (const char c : text) out += (c >= 32 && c < 127) ? c : '?';
  return out;
}

plot::LinePlot score_panel(const std::string& trainee, const std::vector<Attempt>& attempts,
                           const Proficiency& proficiency) {
  const double n = static_cast<double>(std::max<std::size_t>(attempts.size(), 1));
  plot::LinePlot top;
  top.title = ascii(trainee) + ": " + proficiency.headline();
  top.width = 900;
  top.height = 320;
  top.x.label = "attempt";
  top.x.min = 0.5;
  top.x.max = n + 0.5;
  top.y.label = "score (0-100)";
  top.y.min = 0.0;
  top.y.max = 100.0;
  plot::Series line{"", {}, {}, plot::Marker::None, true};
  plot::Series pass{"passed", {}, {}, plot::Marker::Circle, false};
  plot::Series fail{"failed", {}, {}, plot::Marker::Cross, false};
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    const double x = static_cast<double>(i + 1), y = 100.0 * attempts[i].score;
    line.x.push_back(x);
    line.y.push_back(y);
    (attempts[i].passed ? pass : fail).x.push_back(x);
    (attempts[i].passed ? pass : fail).y.push_back(y);
  }
  top.series = {line, pass, fail};
  return top;
}

plot::LinePlot cusum_panel(const plot::Axis& x, double n, const Cusum& cusum, const CusumDesign& design) {
  plot::LinePlot bottom;
  bottom.title = fmt::format("CUSUM of failures: up {:.2f} per failure, down {:.2f} per pass, back to 0 after a signal",
                             1.0 - design.s(), design.s());
  bottom.width = 900;
  bottom.height = 320;
  bottom.x = x;
  bottom.y.label = "CUSUM";
  plot::Series c{"CUSUM", {0.0}, {0.0}, plot::Marker::Circle, true};
  for (std::size_t i = 0; i < cusum.value.size(); ++i) {
    const double at = static_cast<double>(i + 1);
    c.x.push_back(at);
    c.y.push_back(cusum.value[i]);
    if (i < cusum.signal.size() && cusum.signal[i] != CusumSignal::None) {  // the restart, drawn as a drop to 0
      c.x.push_back(at);
      c.y.push_back(0.0);
    }
  }
  double lo = -design.h0(), hi = design.h1();
  for (const double v : cusum.value) lo = std::min(lo, v), hi = std::max(hi, v);
  bottom.y.min = lo - 0.3;
  bottom.y.max = hi + 0.3;
  const auto above = fmt::format("failure rate > {:.0f} %", 100.0 * design.p1);
  const auto below = fmt::format("failure rate < {:.0f} %", 100.0 * design.p0);
  plot::Series h1{above, {0.5, n + 0.5}, {design.h1(), design.h1()}, plot::Marker::None, true};
  plot::Series h0{below, {0.5, n + 0.5}, {-design.h0(), -design.h0()}, plot::Marker::None, true};
  bottom.series = {c, h1, h0};
  return bottom;
}

}  // namespace

cv::Mat learning_curve_plot(const std::string& trainee, const std::vector<Attempt>& attempts, const Cusum& cusum,
                            const Proficiency& proficiency, const CusumDesign& design) {
  const auto top = score_panel(trainee, attempts, proficiency);
  const double n = static_cast<double>(std::max<std::size_t>(attempts.size(), 1));
  cv::Mat image;
  cv::vconcat(plot::render(top), plot::render(cusum_panel(top.x, n, cusum, design)), image);
  return image;
}

namespace {

// 16 hex digits (64 bits) of the text's SHA-1: two names meet by chance about once in
// 4e9 pairs squared, and no one can pick a name that meets a given one.
std::string hash16(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  const auto digest = sha1(text);
  std::string hex;
  for (std::size_t i = 0; i < 8; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 15];
  }
  return hex;
}

// Letters, digits, '.', '_' and '-' kept, anything else '_', no leading '.', at most 48.
std::string readable_prefix(std::string_view text) {
  std::string stem;
  for (const char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '_' || c == '-';
    stem += keep ? c : '_';
  }
  while (!stem.empty() && stem.front() == '.') stem.front() = '_';
  if (stem.size() > 48) stem.resize(48);
  return stem;
}

}  // namespace

std::string trainee_file_stem(std::string_view trainee) {
  const auto prefix = readable_prefix(trainee);
  return (prefix.empty() ? std::string("trainee") : prefix) + "-" + hash16(trainee);
}

std::string case_file_stem(std::string_view case_id) {
  constexpr std::string_view kPrefix = "urn:palpa:case:";
  const auto readable = case_id.substr(0, kPrefix.size()) == kPrefix ? case_id.substr(kPrefix.size()) : case_id;
  const auto prefix = readable_prefix(readable);
  return (prefix.empty() ? std::string("case") : prefix) + "-" + hash16(case_id);
}

}  // namespace palpa::report

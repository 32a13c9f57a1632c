#include "palpa/report/learning_curve.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "palpa/plot/line_plot.hpp"
#include "palpa/report/encoding.hpp"

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
  double value = 0.0, reference = 0.0;
  for (const bool ok : passed) {
    value += ok ? -s : 1.0 - s;
    CusumSignal signal = CusumSignal::None;
    if (value - reference >= h1 - kEps) {
      signal = CusumSignal::Unacceptable;
    } else if (reference - value >= h0 - kEps) {
      signal = CusumSignal::Acceptable;
    }
    if (signal != CusumSignal::None) {
      reference = value;
      c.verdict = signal;
    }
    c.value.push_back(value);
    c.signal.push_back(signal);
  }
  return c;
}

Attempt attempt_of(const SessionHeader& header, const score::Score& score) {
  return {header, score.score, score.passed, score.sensitivity, score.coverage, score.deep_coverage};
}

std::string trainee_csv(const std::vector<Attempt>& attempts, const Cusum& cusum) {
  std::string csv = "attempt,started_at,file,session_id,score,passed,sensitivity,coverage,deep_coverage,cusum,signal\n";
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    const auto& a = attempts[i];
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", i + 1, csv_field(a.header.started_at),
                       csv_field(a.header.file), csv_field(a.header.id), number_text(a.score), a.passed ? "1" : "0",
                       number_text(a.sensitivity), number_text(a.coverage), number_text(a.deep_coverage),
                       i < cusum.value.size() ? number_text(cusum.value[i]) : std::string(),
                       i < cusum.signal.size() ? to_string(cusum.signal[i]) : std::string_view());
  }
  return csv;
}

cv::Mat learning_curve_plot(const std::string& trainee, const std::vector<Attempt>& attempts, const Cusum& cusum,
                            const CusumDesign& design) {
  std::string name;  // Hershey fonts: printable ASCII only
  for (const char c : trainee) name += (c >= 32 && c < 127) ? c : '?';
  const double n = static_cast<double>(std::max<std::size_t>(attempts.size(), 1));
  plot::LinePlot top;
  top.title = "Learning curve: " + name;
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

  plot::LinePlot bottom;
  bottom.title = "CUSUM of failures (p0 0.1, p1 0.3)";
  bottom.width = 900;
  bottom.height = 320;
  bottom.x = top.x;
  bottom.y.label = "CUSUM";
  plot::Series c{"CUSUM", {0.0}, {0.0}, plot::Marker::Circle, true};
  for (std::size_t i = 0; i < cusum.value.size(); ++i) {
    c.x.push_back(static_cast<double>(i + 1));
    c.y.push_back(cusum.value[i]);
  }
  double lo = -design.h0(), hi = design.h1();
  for (const double v : cusum.value) lo = std::min(lo, v), hi = std::max(hi, v);
  bottom.y.min = lo - 0.3;
  bottom.y.max = hi + 0.3;
  plot::Series h1{"h1 unacceptable", {0.5, n + 0.5}, {design.h1(), design.h1()}, plot::Marker::None, true};
  plot::Series h0{"-h0 acceptable", {0.5, n + 0.5}, {-design.h0(), -design.h0()}, plot::Marker::None, true};
  bottom.series = {c, h1, h0};
  cv::Mat image;
  cv::vconcat(plot::render(top), plot::render(bottom), image);
  return image;
}

std::string trainee_file_stem(std::string_view trainee) {
  std::string stem;
  for (const char c : trainee) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '_' || c == '-';
    stem += keep ? c : '_';
  }
  while (!stem.empty() && stem.front() == '.') stem.front() = '_';
  if (stem.size() > 64) stem.resize(64);
  if (stem != trainee || stem.empty()) {
    static constexpr char kHex[] = "0123456789abcdef";
    const auto digest = sha1(trainee);
    stem += stem.empty() ? "trainee-" : "-";
    for (std::size_t i = 0; i < 4; ++i) {
      stem += kHex[digest[i] >> 4];
      stem += kHex[digest[i] & 15];
    }
  }
  return stem;
}

}  // namespace palpa::report

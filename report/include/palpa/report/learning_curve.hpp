#pragma once
// A trainee's learning curve over attempts, with the learning-curve CUSUM of failures of
// Bolsin & Colson (2000), a sequential probability ratio test (Wald) drawn as a chart:
//
//   P = ln(p1 / p0),  Q = ln((1 - p0) / (1 - p1)),  s = Q / (P + Q)
//   each attempt adds 1 - s when it failed and subtracts s when it passed
//   (so the chart drifts down at a failure rate below s and up above it);
//   h1 = ln((1 - beta) / alpha) / (P + Q)   upper decision limit: failure rate unacceptable
//   h0 = ln((1 - alpha) / beta) / (P + Q)   lower decision limit: failure rate acceptable
//
// with p0 = 0.1 (acceptable failure rate), p1 = 0.3 (unacceptable), alpha = beta = 0.1:
// s = 0.1862, h0 = h1 = 1.6277. A signal is given when the chart reaches h1 (failure rate
// probably above p1) or -h0 (probably below p0); the chart then restarts at 0: a new test
// begins, speaking of the attempts since the signal, and the line can be read against the
// two fixed limits drawn (the same signals as measuring from the last signal's value,
// drawn so that the plot says what the test does). A limit reached
// counts: two failures in a row give 2 (1 - s) = ln 9 / (P + Q) = h1 exactly, and nine
// passes in a row 9 s = 1.676 >= h0. The headline verdict is not this chart but the
// proficiency rule (proficiency.hpp); the chart is its supporting evidence.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "palpa/report/proficiency.hpp"
#include "palpa/report/session_header.hpp"
#include "palpa/score/score.hpp"

namespace palpa::report {

struct CusumDesign {
  double p0 = 0.1, p1 = 0.3, alpha = 0.1, beta = 0.1;
  double s() const;   ///< the reference value subtracted per attempt
  double h0() const;  ///< lower decision limit (acceptable), > 0: the chart falls by this much
  double h1() const;  ///< upper decision limit (unacceptable)
};

enum class CusumSignal { None, Acceptable, Unacceptable };

/// "acceptable", "unacceptable", or `none_text` for None.
std::string_view to_string(CusumSignal signal, std::string_view none_text = "");

struct Cusum {
  std::vector<double> value;         ///< after each attempt (the value reached, at a signal too)
  std::vector<CusumSignal> signal;   ///< signal given at each attempt (mostly None)
  CusumSignal verdict = CusumSignal::None;  ///< the last signal
};

/// The CUSUM of failures over attempts in order (true: the attempt passed), restarted at 0
/// after each signal.
Cusum failure_cusum(const std::vector<bool>& passed, const CusumDesign& design = {});

/// The chart in words, for the page under it: "Each failure raises the line by 0.81, each
/// pass lowers it by 0.19; touching the upper line (1.63) means the failure rate is probably
/// above 30 %, the lower (-1.63) below 10 %; the line then restarts at 0."
std::string cusum_caption(const CusumDesign& design = {});

/// The last signal in words: "failure rate probably above 30 % (attempt 2)", "... below
/// 10 % (attempt 9)", or "no signal yet".
std::string cusum_words(const Cusum& cusum, const CusumDesign& design = {});

/// One scored session of a trainee, as kept by a batch (no samples, no maps).
struct Attempt {
  SessionHeader header;
  double score = 0.0;
  bool passed = false;
  double sensitivity = 0.0, coverage = 0.0, deep_coverage = 0.0;
};
Attempt attempt_of(const SessionHeader& header, const score::Score& score);

/// attempt,started_at,file,session_id,score,passed,sensitivity,coverage,deep_coverage,cusum,signal,
/// score_100,proficient,verdict,station (attempt from 1; station: who recorded (or pushed) it; score and shares 0..1; passed 1/0; cusum after
/// the attempt; signal acceptable/unacceptable or empty; proficient 1/0 and the verdict in
/// words after the attempt). Numbers rounded per csv_number.hpp.
std::string trainee_csv(const std::vector<Attempt>& attempts, const Cusum& cusum, const Proficiency& proficiency);

/// Score per attempt (pass/fail markers, the verdict in the title) above the CUSUM with its
/// decision limits, captioned in words.
cv::Mat learning_curve_plot(const std::string& trainee, const std::vector<Attempt>& attempts, const Cusum& cusum,
                            const Proficiency& proficiency, const CusumDesign& design = {});

/// A file name stem (and page anchor) for a trainee id: a readable prefix (letters, digits,
/// '.', '_' and '-' kept, anything else turned into '_', no leading '.', at most 48
/// characters), "-" and 16 hex digits of the exact id's SHA-1, always: two different ids
/// never share a file, even when their prefixes agree ("al ice", "al_ice-1373f329") or
/// differ only in case on a file system that ignores it ("Alice", "alice").
std::string trainee_file_stem(std::string_view trainee);

/// A file name stem for a case id: the same with the readable prefix taken from the slug of
/// "urn:palpa:case:SLUG" ("default-" and the hash of the whole id).
std::string case_file_stem(std::string_view case_id);

}  // namespace palpa::report

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
// s = 0.1862, h0 = h1 = 1.6277. Read as repeated tests: a signal is given when the CUSUM
// has fallen h0 below, or risen h1 above, its value at the last signal (0 at the start);
// each signal restarts the test from there. The verdict is the last signal, "undecided"
// before the first. With these limits a trainee who passes every attempt is judged
// acceptable after 9 attempts (9 s = 1.68 >= h0), and two failures in a row reach h1
// exactly (2 (1 - s) = 2 P / (P + Q) = ln 9 / (P + Q) = h1): a limit reached counts.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

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
  std::vector<double> value;         ///< after each attempt
  std::vector<CusumSignal> signal;   ///< signal given at each attempt (mostly None)
  CusumSignal verdict = CusumSignal::None;  ///< the last signal
};

/// The CUSUM of failures over attempts in order (true: the attempt passed).
Cusum failure_cusum(const std::vector<bool>& passed, const CusumDesign& design = {});

/// One scored session of a trainee, as kept by a batch (no samples, no maps).
struct Attempt {
  SessionHeader header;
  double score = 0.0;
  bool passed = false;
  double sensitivity = 0.0, coverage = 0.0, deep_coverage = 0.0;
};
Attempt attempt_of(const SessionHeader& header, const score::Score& score);

/// attempt,started_at,file,session_id,score,passed,sensitivity,coverage,deep_coverage,cusum,signal
/// (attempt from 1; score 0..1; passed 1/0; signal acceptable/unacceptable or empty).
std::string trainee_csv(const std::vector<Attempt>& attempts, const Cusum& cusum);

/// Score per attempt (pass/fail markers) above the CUSUM with its decision limits.
cv::Mat learning_curve_plot(const std::string& trainee, const std::vector<Attempt>& attempts, const Cusum& cusum,
                            const CusumDesign& design = {});

/// A file name stem for a trainee id: letters, digits, '.', '_' and '-' kept, anything else
/// turned into '_', no leading '.', at most 64 characters; when that changed the id (or it
/// was empty), "-" and 8 hex digits of the id's SHA-1 are appended so that different ids
/// never share a file.
std::string trainee_file_stem(std::string_view trainee);

}  // namespace palpa::report

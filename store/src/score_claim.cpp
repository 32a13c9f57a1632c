#include "palpa/store/score_claim.hpp"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "palpa/report/session_filter.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/store/sha256.hpp"
#include "palpa/version.hpp"

namespace palpa::store {
namespace {

// The first field of the file's head (all but the samples) in which the file and the
// store's row disagree, or "".
std::string mismatch(const session::Session& s, const Claim& claim) {
  if (s.info.id != claim.session_id) return "id";
  if (s.info.trainee != claim.trainee) return "trainee";
  if (session::session_mode(s.info) != claim.mode) return "mode";
  const auto started = report::parse_iso8601(s.info.started_at);
  if (!started || std::abs(*started - claim.started_at_s) > 1.0) return "start date";
  if (!s.complete) return "end event";
  const auto stored_case = nlohmann::json::parse(claim.case_document, nullptr, false);
  if (stored_case.is_discarded() || stored_case != s.info.case_document) return "case";
  return {};
}

[[noreturn]] void refuse(const Claim& claim, const std::string& field) {
  throw session::SessionError(
      describe(claim), "meta", fmt::format("the file's {} differs from what the station sent with it; not scored", field));
}

// Scores as a stream: memory bounded by the case, whatever the number of ticks.
ScoreRow score_checked(session::SampleStream& stream, const Claim& claim) {
  if (const auto field = mismatch(stream.head(), claim); !field.empty()) refuse(claim, field);
  const auto score = score::score_stream(stream, claim.file_name);
  if (static_cast<long long>(stream.count()) != claim.samples) refuse(claim, "sample count");
  ScoreRow row;
  row.scorer_version = palpa::kVersion;
  row.thresholds_sha256 = sha256_hex(score::to_json(score.thresholds).dump());
  row.result_json = score::to_json(score, false).dump();  // no maps: they are about 1 MB of JSON
  row.score = score.score;
  row.passed = score.passed;
  return row;
}

}  // namespace

ScoreRow score_claim_bytes(const std::string& bytes, const Claim& claim) {
  session::SampleStream stream(bytes, describe(claim));
  return score_checked(stream, claim);
}

}  // namespace palpa::store

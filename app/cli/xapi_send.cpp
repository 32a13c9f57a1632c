#include "xapi_send.hpp"

#include <exception>

#include "lrs_delivery.hpp"
#include "palpa/lrs/statement_outbox.hpp"
#include "palpa/report/xapi.hpp"

namespace palpa::cli {

std::optional<lrs::LrsConfig> xapi_settings(const ReportRequest& request) {
  try {
    return lrs::load_lrs_config(request.lrs);
  } catch (const std::exception& e) {
    print_error(e.what());
    return std::nullopt;
  }
}

int send_statement(const report::SessionHeader& header, const score::Score& score, const ReportRequest& request,
                   const lrs::LrsConfig& config) {
  const bool asked = !request.lrs.empty() || (request.lrs_when_configured && !config.endpoint.empty());
  if (!asked) return kOk;
  try {
    lrs::StatementOutbox outbox(config.outbox);
    outbox.add(report::xapi_statement(header, score, config.home_page));
    const int delivered = deliver_outbox(config, outbox, 3);
    return delivered == kOk || delivered == kQueued ? kOk : kFailure;
  } catch (const std::exception& e) {
    print_error(e.what());
    return kFailure;
  }
}

}  // namespace palpa::cli

namespace palpa::cli {

void add_lrs_option(CLI::App* app, ReportRequest& request) {
  app->add_option("--lrs", request.lrs,
                  "send the session's xAPI statement to this learning record store (xAPI endpoint, e.g. "
                  "https://lrs.example/xapi; credentials from ~/.netrc); it waits in the outbox while the LRS is "
                  "unreachable (palpa-cli lrs status). The actor's homePage: PALPA_XAPI_HOME_PAGE or "
                  "~/.config/palpa/lrs.json");
}

}  // namespace palpa::cli

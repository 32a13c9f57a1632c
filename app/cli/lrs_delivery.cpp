#include "lrs_delivery.hpp"

#include <cstdio>

#include <fmt/format.h>

#include "commands.hpp"

namespace palpa::cli {

int deliver_outbox(const lrs::LrsConfig& config, lrs::StatementOutbox& outbox, int attempts) {
  if (config.endpoint.empty()) {
    print_error(fmt::format("no learning record store configured (--lrs, PALPA_LRS or {}); the statements wait in {}",
                            lrs::default_config_file().string(), outbox.folder().string()));
    return kBadInput;
  }
  const std::string where = lrs::statements_url_for_display(config.endpoint);
  const lrs::FlushReport r = lrs::deliver(outbox, config.endpoint, attempts);
  if (r.waiting > 0) {
    std::fprintf(stderr, "lrs: %d sent to %s; %d waiting in %s (%s)\n", r.stored, where.c_str(), r.waiting,
                 outbox.folder().c_str(), r.last_reason.c_str());
    return kQueued;
  }
  if (r.rejected > 0) {
    print_error(fmt::format("{} statement(s) rejected by {} ({}); kept in {}", r.rejected, where, r.last_reason,
                            (outbox.folder() / "rejected").string()));
    return kBadInput;
  }
  std::fprintf(stderr, "lrs: %d sent to %s\n", r.stored, where.c_str());
  return kOk;
}

}  // namespace palpa::cli

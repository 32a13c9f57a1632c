// palpa-cli lrs send|flush|status: the station's xAPI statements on their way to a
// learning record store (docs/centre.md, "Learning record store"). Statements wait in an
// outbox folder until the LRS has them; nothing is lost while it is unreachable.
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "lrs_delivery.hpp"
#include "palpa/lrs/lrs_config.hpp"
#include "palpa/lrs/statement_outbox.hpp"

namespace palpa::cli {
namespace {

struct LrsOptions {
  std::vector<std::string> statements;
  std::string endpoint;
  std::string outbox;
  int attempts = 3;
};

lrs::LrsConfig config_of(const LrsOptions& o) {
  lrs::LrsConfig config = lrs::load_lrs_config(o.endpoint);
  if (!o.outbox.empty()) config.outbox = o.outbox;
  return config;
}

int run_send(const LrsOptions& o) {
  const lrs::LrsConfig config = config_of(o);
  lrs::StatementOutbox outbox(config.outbox);
  for (const auto& file : o.statements) {
    std::ifstream in(file);
    const nlohmann::json statement =
        in ? nlohmann::json::parse(in, nullptr, false) : nlohmann::json(nlohmann::json::value_t::discarded);
    if (!in || statement.is_discarded() || !statement.is_object()) {
      print_error(fmt::format("{}: not a JSON xAPI statement", file));
      return kBadInput;
    }
    if (!statement.contains("id") || !statement["id"].is_string()) {
      print_error(fmt::format("{}: id: missing (Palpa's statements carry one)", file));
      return kBadInput;
    }
    outbox.add(statement);
  }
  return deliver_outbox(config, outbox, o.attempts);
}

int run_flush(const LrsOptions& o) {
  const lrs::LrsConfig config = config_of(o);
  lrs::StatementOutbox outbox(config.outbox);
  return deliver_outbox(config, outbox, o.attempts);
}

int run_status(const LrsOptions& o) {
  const lrs::LrsConfig config = config_of(o);
  const lrs::StatementOutbox outbox(config.outbox);
  const auto entries = outbox.list();
  std::printf("outbox: %s\n", outbox.folder().c_str());
  std::printf("lrs: %s\n", config.endpoint.empty() ? "(none configured)"
                                                     : lrs::statements_url_for_display(config.endpoint).c_str());
  int waiting = 0;
  for (const auto& e : entries) {
    waiting += e.rejected ? 0 : 1;
    std::string error = e.last_error;
    while (!error.empty() && error.back() == '\n') error.pop_back();
    std::printf("%s %s trainee=%s started=%s%s%s\n", e.rejected ? "rejected" : "waiting", e.statement_id.c_str(),
                e.actor.c_str(), e.timestamp.c_str(), error.empty() ? "" : " last-error=", error.c_str());
  }
  std::printf("%d waiting, %zu rejected\n", waiting, entries.size() - static_cast<std::size_t>(waiting));
  return kOk;
}

void add_common_options(CLI::App* app, LrsOptions& o) {
  app->add_option("--outbox", o.outbox, "outbox folder; default from the config file, else "
                                        "$XDG_DATA_HOME/palpa/xapi-outbox (~/.local/share/palpa/xapi-outbox)");
}

void add_endpoint_options(CLI::App* app, LrsOptions& o) {
  app->add_option("--lrs", o.endpoint, "the LRS's xAPI endpoint, e.g. https://lrs.example/xapi; default PALPA_LRS "
                                       "or the config file ~/.config/palpa/lrs.json. Credentials: ~/.netrc");
  app->add_option("--attempts", o.attempts, "tries while the LRS is unreachable (0.5 s, 1 s, 2 s ... apart)")
      ->check(CLI::Range(1, 20));
}

}  // namespace

Command add_lrs_command(CLI::App& parent) {
  auto o = std::make_shared<LrsOptions>();
  auto* app = parent.add_subcommand(
      "lrs", "xAPI statements to a learning record store: send files, retry the outbox, list what waits. "
             "Exit 0 when every statement reached the LRS (status: always), 3 when some wait in the outbox "
             "(the LRS is unreachable), 2 for bad input or statements the LRS rejected.");
  app->require_subcommand(1);
  auto* send = app->add_subcommand("send", "queue xAPI statement files (STEM.xapi.json) and send the outbox");
  send->add_option("STATEMENT", o->statements, "statement files")->required()->check(CLI::ExistingFile);
  add_endpoint_options(send, *o);
  add_common_options(send, *o);
  auto* flush = app->add_subcommand("flush", "send the statements waiting in the outbox");
  add_endpoint_options(flush, *o);
  add_common_options(flush, *o);
  auto* status = app->add_subcommand("status", "list the statements waiting in the outbox and those the LRS rejected");
  add_common_options(status, *o);
  return {app, [o, send, flush] {
            if (send->parsed()) return run_send(*o);
            if (flush->parsed()) return run_flush(*o);
            return run_status(*o);
          }};
}

}  // namespace palpa::cli

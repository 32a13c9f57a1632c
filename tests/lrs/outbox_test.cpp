// The xAPI outbox against a fake LRS: what leaves, what stays, in which order, what is
// set aside; and the config file's errors. The real LRS is exercised by cli.lrs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "palpa/lrs/lrs_client.hpp"
#include "palpa/lrs/lrs_config.hpp"
#include "palpa/lrs/statement_outbox.hpp"

namespace fs = std::filesystem;
using palpa::lrs::Delivery;
using palpa::lrs::SendResult;
using palpa::lrs::StatementOutbox;

namespace {

fs::path fresh_folder(const std::string& name) {
  static std::atomic<int> counter{0};
  const fs::path p = fs::temp_directory_path() / ("palpa-outbox-" + std::to_string(::getpid()) + "-" +
                                                  std::to_string(counter++) + "-" + name);
  fs::remove_all(p);
  return p;
}

nlohmann::json statement(int n) {
  return {{"id", "00000000-0000-4000-8000-00000000000" + std::to_string(n)},
          {"actor", {{"objectType", "Agent"}, {"account", {{"homePage", "urn:palpa"}, {"name", "t" + std::to_string(n)}}}}},
          {"timestamp", "2026-12-0" + std::to_string(n) + "T10:00:00Z"}};
}

// Adds statements 1..n with increasing file times, so "oldest first" is well defined.
void add_in_order(StatementOutbox& outbox, int n) {
  for (int i = 1; i <= n; ++i) {
    const fs::path f = outbox.add(statement(i));
    fs::last_write_time(f, fs::file_time_type::clock::now() - std::chrono::hours(n - i + 1));
  }
}

}  // namespace

TEST(Outbox, StoredStatementsLeaveInTheOrderTheyWereMade) {
  StatementOutbox outbox(fresh_folder("order"));
  add_in_order(outbox, 3);
  std::vector<std::string> sent;
  const auto report = outbox.flush([&sent](const nlohmann::json& s) {
    sent.push_back(s["id"]);
    return SendResult{Delivery::Stored, 204, ""};
  });
  EXPECT_EQ(report.stored, 3);
  EXPECT_EQ(report.waiting, 0);
  ASSERT_EQ(sent.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(sent[static_cast<std::size_t>(i)], statement(i + 1)["id"]);
  EXPECT_TRUE(outbox.list().empty());
}

TEST(Outbox, AnUnreachableLrsKeepsEveryStatementNotYetStored) {
  StatementOutbox outbox(fresh_folder("down"));
  add_in_order(outbox, 4);
  int calls = 0;
  const auto report = outbox.flush([&calls](const nlohmann::json&) {
    ++calls;
    return calls == 1 ? SendResult{Delivery::Stored, 200, ""} : SendResult{Delivery::Unreachable, 0, "refused"};
  });
  EXPECT_EQ(calls, 2);  // stops at the first failure instead of hammering a server that is down
  EXPECT_EQ(report.stored, 1);
  EXPECT_EQ(report.waiting, 3);
  const auto left = outbox.list();
  ASSERT_EQ(left.size(), 3u);
  EXPECT_EQ(left[0].statement_id, statement(2)["id"]);
  EXPECT_EQ(left[0].last_error, "refused\n");
  EXPECT_EQ(left[0].actor, "t2");
  EXPECT_TRUE(left[1].last_error.empty());
  // Once the LRS is back, the rest goes and the error notes go with them.
  const auto later = outbox.flush([](const nlohmann::json&) { return SendResult{Delivery::Stored, 204, ""}; });
  EXPECT_EQ(later.stored, 3);
  EXPECT_TRUE(fs::is_empty(outbox.folder()));
}

TEST(Outbox, RejectedStatementsAreSetAsideWithTheirReasonAndTheRestGoesOn) {
  StatementOutbox outbox(fresh_folder("reject"));
  add_in_order(outbox, 3);
  const auto report = outbox.flush([](const nlohmann::json& s) {
    return s["id"] == statement(2)["id"] ? SendResult{Delivery::Rejected, 400, "HTTP 400: bad actor"}
                                         : SendResult{Delivery::Stored, 204, ""};
  });
  EXPECT_EQ(report.stored, 2);
  EXPECT_EQ(report.rejected, 1);
  const auto left = outbox.list();
  ASSERT_EQ(left.size(), 1u);
  EXPECT_TRUE(left[0].rejected);
  EXPECT_EQ(left[0].last_error, "HTTP 400: bad actor\n");
  EXPECT_TRUE(fs::exists(outbox.folder() / "rejected" / (statement(2)["id"].get<std::string>() + ".json")));
  // A rejected statement is not sent again.
  int calls = 0;
  outbox.flush([&calls](const nlohmann::json&) { return ++calls, SendResult{Delivery::Stored, 204, ""}; });
  EXPECT_EQ(calls, 0);
}

TEST(Outbox, AddingTheSameStatementTwiceQueuesItOnce) {
  StatementOutbox outbox(fresh_folder("twice"));
  outbox.add(statement(1));
  outbox.add(statement(1));
  EXPECT_EQ(outbox.list().size(), 1u);
}

TEST(Outbox, ADamagedFileIsSetAsideNotSentNorLost) {
  StatementOutbox outbox(fresh_folder("damaged"));
  outbox.add(statement(1));
  std::ofstream(outbox.folder() / "00000000-0000-4000-8000-000000000009.json") << "{\"id\": \"trunc";
  int calls = 0;
  const auto report =
      outbox.flush([&calls](const nlohmann::json&) { return ++calls, SendResult{Delivery::Stored, 204, ""}; });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(report.rejected, 1);
  EXPECT_TRUE(fs::exists(outbox.folder() / "rejected" / "00000000-0000-4000-8000-000000000009.json"));
}

TEST(Outbox, AStatementIdThatIsNotAUuidIsRefusedBeforeItNamesAFile) {
  StatementOutbox outbox(fresh_folder("id"));
  EXPECT_THROW(outbox.add({{"id", "../../etc/passwd"}}), std::runtime_error);
  EXPECT_THROW(outbox.add({{"actor", "x"}}), std::runtime_error);
  EXPECT_TRUE(fs::is_empty(outbox.folder()));
}

TEST(LrsUrl, CredentialsInTheEndpointAreNeverShown) {
  EXPECT_EQ(palpa::lrs::statements_url_for_display("https://key:secret@lrs.example/xapi"),
            "https://lrs.example/xapi/statements");
  EXPECT_EQ(palpa::lrs::statements_url_for_display("http://lrs.example/xapi/"), "http://lrs.example/xapi/statements");
  EXPECT_EQ(palpa::lrs::statements_url_for_display("http://lrs.example/a@b"), "http://lrs.example/a@b/statements");
}

TEST(LrsUrl, NothingListeningIsUnreachableNotAnError) {
  const auto r = palpa::lrs::put_statement("http://127.0.0.1:1/xapi", statement(1), 2.0);
  EXPECT_EQ(r.delivery, Delivery::Unreachable);
  EXPECT_EQ(r.http_status, 0);
  EXPECT_FALSE(r.reason.empty());
}

TEST(LrsConfig, TheFileTheEnvironmentAndTheCommandLineInThatOrder) {
  const fs::path dir = fresh_folder("config");
  fs::create_directories(dir);
  const fs::path file = dir / "lrs.json";
  std::ofstream(file) << R"({"endpoint": "https://file.example/xapi", "home_page": "https://sim.example.org"})";
  ::unsetenv("PALPA_LRS");
  ::unsetenv("PALPA_XAPI_HOME_PAGE");
  auto c = palpa::lrs::load_lrs_config("", file);
  EXPECT_EQ(c.endpoint, "https://file.example/xapi");
  EXPECT_EQ(c.home_page, "https://sim.example.org");
  ::setenv("PALPA_LRS", "https://env.example/xapi", 1);
  EXPECT_EQ(palpa::lrs::load_lrs_config("", file).endpoint, "https://env.example/xapi");
  EXPECT_EQ(palpa::lrs::load_lrs_config("https://cli.example/xapi", file).endpoint, "https://cli.example/xapi");
  ::unsetenv("PALPA_LRS");
  EXPECT_EQ(palpa::lrs::load_lrs_config("", dir / "absent.json").home_page, palpa::lrs::kDefaultHomePage);
}

TEST(LrsConfig, AMalformedFileIsNamedWithItsField) {
  const fs::path dir = fresh_folder("badconfig");
  fs::create_directories(dir);
  const fs::path file = dir / "lrs.json";
  auto message_for = [&file](const std::string& text) {
    std::ofstream(file, std::ios::trunc) << text;
    try {
      palpa::lrs::load_lrs_config("", file);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message_for(R"({"endpoint": 3})"), file.string() + ": endpoint: must be a non-empty text");
  EXPECT_EQ(message_for(R"({"endpont": "x"})"), file.string() + ": endpont: unknown field (endpoint, home_page, outbox)");
  EXPECT_EQ(message_for("[1"), file.string() + ": not a JSON object");
}

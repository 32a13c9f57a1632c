#pragma once
// One xAPI 1.0.3 request to a learning record store: PUT /statements?statementId=ID, so
// that sending a statement twice stores it once (xAPI 1.0.3, Part Three, 2.1.1: a PUT of
// an id the LRS already holds with the same content is answered 204 No Content).
// Credentials come from libcurl's own ~/.netrc lookup (or user:password in the URL, which
// Palpa never prints); they are never taken from a command line.
#include <string>

#include <nlohmann/json.hpp>

namespace palpa::lrs {

/// What became of one request.
enum class Delivery {
  Stored,     ///< 2xx: the LRS holds the statement
  Rejected,   ///< 4xx other than 408/429: the LRS will never take it as it is (kept, not retried)
  Unreachable ///< no answer, a timeout, 408, 429 or 5xx: worth trying again later
};

struct SendResult {
  Delivery delivery = Delivery::Unreachable;
  long http_status = 0;  ///< 0 when no HTTP answer came
  std::string reason;    ///< one line for people: the LRS's message or the transport error
};

/// The statements resource of an LRS endpoint ("https://lrs.example/xapi" or ".../xapi/"),
/// without credentials, for messages: "https://lrs.example/xapi/statements".
std::string statements_url_for_display(const std::string& endpoint);

/// Sends `statement` (which must have an "id") with PUT; never throws for network errors.
/// `timeout_s` bounds the whole request.
SendResult put_statement(const std::string& endpoint, const nlohmann::json& statement, double timeout_s = 10.0);

}  // namespace palpa::lrs

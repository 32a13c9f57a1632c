#include "palpa/lrs/lrs_client.hpp"

#include <curl/curl.h>

#include <memory>
#include <mutex>

#include <fmt/format.h>

namespace palpa::lrs {
namespace {

// The endpoint with "statements" appended, whatever its trailing slash.
std::string statements_url(const std::string& endpoint) {
  return endpoint + (!endpoint.empty() && endpoint.back() == '/' ? "" : "/") + "statements";
}

std::size_t append_body(char* data, std::size_t size, std::size_t count, void* out) {
  auto* body = static_cast<std::string*>(out);
  if (body->size() < 4096) body->append(data, size * count);  // enough for a message
  return size * count;
}

// A short reason from the LRS's answer: its "message" or "warnings" when JSON, else the text.
std::string reason_from_body(long status, const std::string& body) {
  std::string detail = body.substr(0, 300);
  const auto json = nlohmann::json::parse(body, nullptr, false);
  if (json.is_object()) {
    if (json.contains("warnings")) detail = json["warnings"].dump();
    else if (json.contains("message") && json["message"].is_string()) detail = json["message"].get<std::string>();
  }
  for (char& c : detail) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return fmt::format("HTTP {}{}{}", status, detail.empty() ? "" : ": ", detail);
}

Delivery delivery_of(long status) {
  if (status >= 200 && status < 300) return Delivery::Stored;
  if (status == 408 || status == 429 || status >= 500) return Delivery::Unreachable;
  return Delivery::Rejected;
}

struct CurlDeleter {
  void operator()(CURL* c) const { curl_easy_cleanup(c); }
};
struct SlistDeleter {
  void operator()(curl_slist* s) const { curl_slist_free_all(s); }
};

}  // namespace

std::string statements_url_for_display(const std::string& endpoint) {
  std::string url = statements_url(endpoint);
  // Drop "user:password@" from the authority, should the endpoint carry credentials.
  const auto scheme = url.find("://");
  const auto start = scheme == std::string::npos ? 0 : scheme + 3;
  const auto at = url.find('@', start);
  const auto slash = url.find('/', start);
  if (at != std::string::npos && (slash == std::string::npos || at < slash)) url.erase(start, at + 1 - start);
  return url;
}

SendResult put_statement(const std::string& endpoint, const nlohmann::json& statement, double timeout_s) {
  static std::once_flag init;
  std::call_once(init, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
  const std::unique_ptr<CURL, CurlDeleter> curl(curl_easy_init());
  if (!curl) return {Delivery::Unreachable, 0, "cannot start libcurl"};
  const std::string url = statements_url(endpoint) + "?statementId=" + statement.value("id", std::string());
  const std::string payload = statement.dump();
  std::unique_ptr<curl_slist, SlistDeleter> headers(curl_slist_append(nullptr, "Content-Type: application/json"));
  headers.reset(curl_slist_append(headers.release(), "X-Experience-API-Version: 1.0.3"));
  std::string body;
  CURL* c = curl.get();
  curl_easy_setopt(c, CURLOPT_URL, url.c_str());
  curl_easy_setopt(c, CURLOPT_CUSTOMREQUEST, "PUT");
  curl_easy_setopt(c, CURLOPT_POSTFIELDS, payload.c_str());
  curl_easy_setopt(c, CURLOPT_POSTFIELDSIZE, static_cast<long>(payload.size()));
  curl_easy_setopt(c, CURLOPT_HTTPHEADER, headers.get());
  curl_easy_setopt(c, CURLOPT_NETRC, static_cast<long>(CURL_NETRC_OPTIONAL));
  curl_easy_setopt(c, CURLOPT_TIMEOUT_MS, static_cast<long>(timeout_s * 1000.0));
  curl_easy_setopt(c, CURLOPT_CONNECTTIMEOUT_MS, static_cast<long>(timeout_s * 500.0));
  curl_easy_setopt(c, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(c, CURLOPT_WRITEFUNCTION, append_body);
  curl_easy_setopt(c, CURLOPT_WRITEDATA, &body);
  const CURLcode code = curl_easy_perform(c);
  if (code != CURLE_OK) return {Delivery::Unreachable, 0, curl_easy_strerror(code)};
  long status = 0;
  curl_easy_getinfo(c, CURLINFO_RESPONSE_CODE, &status);
  const Delivery delivery = delivery_of(status);
  return {delivery, status, delivery == Delivery::Stored ? std::string() : reason_from_body(status, body)};
}

}  // namespace palpa::lrs

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "palpa/report/images.hpp"
#include "palpa/report/session_html.hpp"
#include "report_fixture.hpp"

namespace palpa::report {
namespace {

/// Standard base64 decoding (independent of the encoder under test).
std::vector<std::uint8_t> decode_base64(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::uint32_t buffer = 0;
  int bits = 0;
  for (const char c : text) {
    int v = -1;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    if (c >= '0' && c <= '9') v = c - '0' + 52;
    if (c == '+') v = 62;
    if (c == '/') v = 63;
    if (v < 0) continue;  // '=' padding
    buffer = (buffer << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((buffer >> bits) & 0xFFu));
    }
  }
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

SessionImages small_images() {
  // Real figures of the synthetic score (the force panel without samples).
  const auto score = testing::synthetic_score();
  return render_images(session::Session{}, score);
}

TEST(SessionHtml, EscapesHostileText) {
  auto h = testing::synthetic_header();
  h.trainee = "<script>alert('x')</script>";
  h.case_title = "Case \"A\" & <b>B</b>";
  const auto html = session_html(h, testing::synthetic_score(), small_images());
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(html.find("Case &quot;A&quot; &amp; &lt;b&gt;B&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(html.find("a note with &lt;b&gt;markup&lt;/b&gt; &amp; ampersand"), std::string::npos);
}

TEST(SessionHtml, EmbedsThreeDecodablePngsAndNoExternalAsset) {
  const auto html = session_html(testing::synthetic_header(), testing::synthetic_score(), small_images());
  const std::string prefix = "src=\"data:image/png;base64,";
  EXPECT_EQ(count(html, "<img "), 3u);
  std::size_t decoded = 0;
  for (auto at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at + 1)) {
    const auto begin = at + prefix.size();
    const auto end = html.find('"', begin);
    ASSERT_NE(end, std::string::npos);
    const auto image = cv::imdecode(decode_base64(html.substr(begin, end - begin)), cv::IMREAD_COLOR);
    EXPECT_FALSE(image.empty());
    EXPECT_GT(image.cols, 100);
    ++decoded;
  }
  EXPECT_EQ(decoded, 3u);
  EXPECT_EQ(count(html, "http://"), 0u);
  EXPECT_EQ(count(html, "https://"), 0u);
  EXPECT_EQ(count(html, "<link"), 0u);
  EXPECT_EQ(count(html, "<script"), 0u);
}

TEST(SessionHtml, ShowsVerdictGatesTumoursMarksAndThresholds) {
  auto s = testing::synthetic_score();
  s.score = 0.734;
  const auto html = session_html(testing::synthetic_header(), s, small_images());
  EXPECT_NE(html.find("FAILED"), std::string::npos);
  EXPECT_NE(html.find("You found 1 of 2 tumours."), std::string::npos);
  EXPECT_NE(html.find("You covered 40 % of the region; 90 % is needed."), std::string::npos);
  EXPECT_NE(html.find("73.4 / 100"), std::string::npos);
  EXPECT_NE(html.find("false positive"), std::string::npos);
  EXPECT_NE(html.find("hit tumour 1"), std::string::npos);
  EXPECT_NE(html.find("10.0 mm"), std::string::npos);  // tumour 1: diameter 10 mm; hit margin 10 mm
  EXPECT_NE(html.find("20.0 N"), std::string::npos);   // safety limit
  s.passed = true;
  EXPECT_NE(session_html(testing::synthetic_header(), s, small_images()).find("PASSED"), std::string::npos);
}

}  // namespace
}  // namespace palpa::report

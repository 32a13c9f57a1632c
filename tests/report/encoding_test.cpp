#include "palpa/report/encoding.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace palpa::report {
namespace {

std::string hex(const std::array<std::uint8_t, 20>& d) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string s;
  for (const auto b : d) s += {kHex[b >> 4], kHex[b & 15]};
  return s;
}

TEST(Encoding, Base64MatchesTheRfc4648Vectors) {
  EXPECT_EQ(base64(std::string_view("")), "");
  EXPECT_EQ(base64(std::string_view("f")), "Zg==");
  EXPECT_EQ(base64(std::string_view("fo")), "Zm8=");
  EXPECT_EQ(base64(std::string_view("foo")), "Zm9v");
  EXPECT_EQ(base64(std::string_view("foob")), "Zm9vYg==");
  EXPECT_EQ(base64(std::string_view("fooba")), "Zm9vYmE=");
  EXPECT_EQ(base64(std::string_view("foobar")), "Zm9vYmFy");
}

TEST(Encoding, Base64OfHighBytes) {
  std::vector<std::uint8_t> bytes(256);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i);
  const auto text = base64(bytes);
  EXPECT_EQ(text.size(), 344u);  // 4 * ceil(256 / 3)
  EXPECT_EQ(text.substr(0, 40), "AAECAwQFBgcICQoLDA0ODxAREhMUFRYXGBkaGxwd");  // Python's base64
  EXPECT_EQ(text.substr(text.size() - 8), "/P3+/w==");
  EXPECT_EQ(base64(std::vector<std::uint8_t>{0xFF, 0xFE}), "//4=");
}

TEST(Encoding, Sha1MatchesTheFipsVectors) {
  EXPECT_EQ(hex(sha1("")), "da39a3ee5e6b4b0d3255bfef95601890afd80709");
  EXPECT_EQ(hex(sha1("abc")), "a9993e364706816aba3e25717850c26c9cd0d89d");
  EXPECT_EQ(hex(sha1("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "84983e441c3bd26ebaae4aa1f95129e5e54670f1");
  EXPECT_EQ(hex(sha1(std::string(1000000, 'a'))), "34aa973cd4c4daa4f61eeb2bdbad27316534016f");
}

TEST(Encoding, UuidV5MatchesPython) {
  // uuid.uuid5(uuid.NAMESPACE_DNS, "python.org") and uuid.uuid5(uuid.NAMESPACE_URL, "urn:palpa")
  EXPECT_EQ(uuid_v5("6ba7b810-9dad-11d1-80b4-00c04fd430c8", "python.org"), "886313e1-3b8a-5372-9b90-0c9aee199e5d");
  EXPECT_EQ(uuid_v5("6ba7b811-9dad-11d1-80b4-00c04fd430c8", "urn:palpa"), kPalpaNamespace);
  EXPECT_THROW(uuid_v5("not-a-uuid", "x"), std::invalid_argument);
  EXPECT_THROW(uuid_v5("6ba7b8109dad11d180b400c04fd430c8", "x"), std::invalid_argument);
}

TEST(Encoding, HtmlEscapeLeavesNoMarkup) {
  EXPECT_EQ(html_escape("<script>alert('x') & \"y\"</script>"),
            "&lt;script&gt;alert(&#39;x&#39;) &amp; &quot;y&quot;&lt;/script&gt;");
  EXPECT_EQ(html_escape("plain"), "plain");
}

TEST(Encoding, CsvFieldsQuoteOnlyWhenNeeded) {
  EXPECT_EQ(csv_field("alice"), "alice");
  EXPECT_EQ(csv_field("Smith, \"Jo\""), "\"Smith, \"\"Jo\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field(""), "");
  // What a spreadsheet would execute is neutralised (OWASP): a leading ' inside quotes.
  EXPECT_EQ(csv_field("=HYPERLINK(\"http://x\",\"y\")"), "\"'=HYPERLINK(\"\"http://x\"\",\"\"y\"\")\"");
  EXPECT_EQ(csv_field("+1"), "\"'+1\"");
  EXPECT_EQ(csv_field("-2+3"), "\"'-2+3\"");
  EXPECT_EQ(csv_field("@SUM(A1)"), "\"'@SUM(A1)\"");
  EXPECT_EQ(csv_field("\t=1"), "\"'\t=1\"");
  EXPECT_EQ(csv_field("a=b"), "a=b");  // only a leading one counts
}

TEST(Encoding, NumbersReadBackExactly) {
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(183.25), "183.25");
  EXPECT_EQ(number_text(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(number_text(std::nan("")), "");
  EXPECT_EQ(number_text(-INFINITY), "");
}

}  // namespace
}  // namespace palpa::report

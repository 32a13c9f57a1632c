#include "palpa/session/session_id.hpp"

#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace palpa::session {
namespace {

TEST(SessionId, NewIdsAre32LowercaseHexDigitsAndDiffer) {
  std::set<std::string> seen;
  for (int k = 0; k < 1000; ++k) {
    const auto id = new_session_id();
    ASSERT_EQ(id.size(), 32u);
    ASSERT_EQ(id.find_first_not_of("0123456789abcdef"), std::string::npos) << id;
    ASSERT_TRUE(is_session_id(id));
    seen.insert(id);
  }
  EXPECT_EQ(seen.size(), 1000u);  // 128 random bits: a repeat would be a broken source
}

TEST(SessionId, OnlyHexIdsOf32Or16DigitsAreSessionIds) {
  EXPECT_TRUE(is_session_id(std::string(32, 'a')));
  EXPECT_TRUE(is_session_id("0123456789abcdef"));  // older scripted sessions
  const std::vector<std::string> bads{"", "0123456789ABCDEF0123456789abcdef", "0123456789abcde", std::string(33, 'a'),
                                std::string(64, 'a'), "../../../../etc/passwd", "/tmp/x", "0123456789abcdef/",
                                "<script>alert(1)</script>", "0123456789abcdeg", std::string("0123456789abcde\0", 16),
                                "0123456789abcdef0123456789abcde\x1b"};
  for (const auto& bad : bads) {
    EXPECT_FALSE(is_session_id(bad)) << bad;
  }
}

}  // namespace
}  // namespace palpa::session

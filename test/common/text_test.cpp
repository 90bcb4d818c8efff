#include "common/text.hpp"

#include <gtest/gtest.h>

using namespace lcm_control;

TEST(Text, EditDistance) {
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("same", "same"), 0u);
}

TEST(Text, ClosestNameWithinADistance) {
  EXPECT_EQ(closest_name("publish_rat", {"publish_rate", "joints"}, 3), "publish_rate");
  EXPECT_EQ(closest_name("zzzzzzzz", {"publish_rate", "joints"}, 3), "");
}

TEST(Text, TrimJoinSplit) {
  EXPECT_EQ(trim("  a b \n"), "a b");
  EXPECT_EQ(join({"a", "b"}), "a, b");
  EXPECT_EQ(split_words(" -J  a 1 "), (std::vector<std::string>{"-J", "a", "1"}));
}

#include "description/text.hpp"

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

TEST(Text, ClosestNamesNearestFirstWithinADistance) {
  EXPECT_EQ(closest_names("lst", {"load", "list", "unload", "lst2", "list"}, 3, 3),
            (std::vector<std::string>{"list", "lst2", "load"}));
  EXPECT_EQ(closest_names("lst", {"load", "list", "unload", "lst2"}, 3, 2), (std::vector<std::string>{"list", "lst2"}));
  EXPECT_EQ(closest_names("lst", {"load", "list", "lst2"}, 1, 2), (std::vector<std::string>{"list"}));
  EXPECT_TRUE(closest_names("zzzzzzzz", {"list", "load"}, 3, 2).empty());
}

TEST(Text, TrimJoinSplit) {
  EXPECT_EQ(trim("  a b \n"), "a b");
  EXPECT_EQ(join({"a", "b"}), "a, b");
  EXPECT_EQ(split_words(" -J  a 1 "), (std::vector<std::string>{"-J", "a", "1"}));
}

TEST(Text, SplitKeepsEmptyFields) {
  EXPECT_EQ(split("a,,b", ','), (std::vector<std::string>{"a", "", "b"}));
  EXPECT_EQ(split("", ','), (std::vector<std::string>{""}));
  EXPECT_EQ(split("0.1,", ','), (std::vector<std::string>{"0.1", ""}));
}

TEST(Text, ParseDoubleTakesOnlyAFiniteNumber) {
  double v = 0;
  EXPECT_TRUE(parse_double(" -2.5e-1 ", v));
  EXPECT_EQ(v, -0.25);
  for (const char* bad : {"", "  ", "1x", "0.1.2", "nan", "inf", "-inf", "1e999", "abc"})
    EXPECT_FALSE(parse_double(bad, v)) << "'" << bad << "'";
}

// CSV cells: RFC 4180 quoting of text, and the reader getting back exactly
// what CsvWriter wrote (commas, quotes and line breaks inside a message).
#include "tools/lib/messages/csv.hpp"

#include <gtest/gtest.h>

#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control::tools;
using lcm_control::testing::read_text;
using lcm_control::testing::temp_dir;

namespace {
// The message of the std::runtime_error that parse_csv throws, or "" if it parses.
std::string parse_error(const std::string& text) {
  try {
    parse_csv(text, "run.csv");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}
Field number(const std::string& path, double v) { return Field{path, v, 0, false, false, "", ""}; }
Field integer(const std::string& path, int64_t v) { return Field{path, double(v), v, true, false, "", ""}; }
Field text(const std::string& path, const std::string& s) { return Field{path, 0, 0, false, true, s, ""}; }
}  // namespace

TEST(Csv, QuotesOnlyCellsThatNeedIt) {
  for (const std::string plain : {"", "j1", "0.1", "-2", "1234567890123456", "1e-07", "position[0]", "a b"})
    EXPECT_EQ(csv_quote(plain), plain);
  EXPECT_EQ(csv_quote("error 0.5, tolerance 0.1"), "\"error 0.5, tolerance 0.1\"");
  EXPECT_EQ(csv_quote("joint \"j3\""), "\"joint \"\"j3\"\"\"");
  EXPECT_EQ(csv_quote("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_quote("cr\r"), "\"cr\r\"");
  EXPECT_EQ(csv_quote(" leading"), "\" leading\"");
  EXPECT_EQ(csv_quote("trailing "), "\"trailing \"");
  EXPECT_EQ(csv_quote("\""), "\"\"\"\"");
}

TEST(Csv, WriterAndReaderRoundTripTextNextToNumbers) {
  const std::string path = temp_dir("csv_round_trip") + "/status.csv";
  const std::string failure = "goal tolerance violated on joint 'j1': error 0.5, tolerance \"0.1\"\nstopped";
  {
    CsvWriter w(path);
    w.write({integer("utime", 7), number("error[0]", 0.5), text("message", failure), text("joint_names[0]", "j1")});
    w.write({integer("utime", 8), number("error[0]", -2), text("message", " padded "), text("joint_names[0]", "")});
    EXPECT_EQ(w.columns(), 4u);
  }
  const std::string raw = read_text(path);
  EXPECT_EQ(raw.substr(0, raw.find('\n')), "utime,error[0],message,joint_names[0]");
  EXPECT_NE(raw.find("7,0.5,\"goal tolerance violated on joint 'j1': error 0.5, tolerance \"\"0.1\"\"\nstopped\",j1\n"),
            std::string::npos)
      << raw;
  EXPECT_NE(raw.find("\n8,-2,\" padded \",\n"), std::string::npos) << raw;

  const CsvTable t = read_csv(path);
  EXPECT_EQ(t.header, (std::vector<std::string>{"utime", "error[0]", "message", "joint_names[0]"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"7", "0.5", failure, "j1"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"8", "-2", " padded ", ""}));
  EXPECT_EQ(t.column("message"), 2);
  EXPECT_EQ(t.column("msg"), -1);
}

TEST(Csv, ParsesCrlfEmptyCellsAndBlankLines) {
  const CsvTable t = parse_csv("utime,message,data\r\n1,,\"a\r\nb\"\r\n\n2,\"\",\r\n", "run.csv");
  EXPECT_EQ(t.header, (std::vector<std::string>{"utime", "message", "data"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"1", "", "a\r\nb"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"2", "", ""}));
}

TEST(Csv, MalformedTextNamesTheFileLineAndColumn) {
  EXPECT_EQ(parse_error("utime,message\n1,ok\n"), "");
  const std::string unclosed = parse_error("utime,message\n1,ok\n2,\"never\nclosed\n");
  EXPECT_NE(unclosed.find("run.csv:3: column 2: the quoted cell is never closed"), std::string::npos) << unclosed;
  const std::string after = parse_error("utime,message\n1,\"quoted\"tail\n");
  EXPECT_NE(after.find("run.csv:2: column 2: text after the closing quote"), std::string::npos) << after;
  const std::string stray = parse_error("utime,message\n1,say \"hi\"\n");
  EXPECT_NE(stray.find("run.csv:2: column 2: a quote in an unquoted cell"), std::string::npos) << stray;
  const std::string shifted = parse_error("utime,message\n1,\"a,b\"\n2,a,b\n");
  EXPECT_NE(shifted.find("run.csv:3: 3 cells where the header has 2; a cell holding a comma must be quoted"),
            std::string::npos)
      << shifted;
}

TEST(Csv, ReadingAMissingFileSaysWhich) {
  const std::string path = temp_dir("csv_missing") + "/nope.csv";
  try {
    read_csv(path);
    FAIL() << "read_csv of a missing file returned";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read " + path), std::string::npos) << e.what();
  }
}

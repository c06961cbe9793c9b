#include "io/csv.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"

namespace rupture::io {
namespace {

using ::testing::HasSubstr;

TEST(Csv, ParsesCommentsHeaderUnitsAndRows) {
  const auto t = parse_csv("# made by hand\n# second\nstrain[%],force [N]\n0,1.5\n0.5, -2e-3\r\n\n1,+3\n", "t.csv");
  ASSERT_EQ(t.comments.size(), 2u);
  EXPECT_EQ(t.comments[0], "made by hand");
  ASSERT_EQ(t.header.size(), 2u);
  EXPECT_EQ(column_name(t.header[1]), "force");
  EXPECT_EQ(column_unit(t.header[0]), "%");
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_DOUBLE_EQ(t.column("force")[1], -2e-3);
  EXPECT_DOUBLE_EQ(t.column("strain[%]")[2], 1.0);
  EXPECT_EQ(t.line_of_row[2], 7u);
}

TEST(Csv, RoundTripIsExact) {
  const std::vector<double> row{0.1, 1.0 / 3.0, -2.5e-300, 123456789.0, 6.02214076e23};
  const auto text = format_csv_header({"a[1]", "b", "c", "d", "e"}) + format_csv_row(row);
  const auto t = parse_csv(text, "mem");
  for (std::size_t c = 0; c < row.size(); ++c) EXPECT_EQ(t.columns[c][0], row[c]);
}

TEST(Csv, TextInANumberFieldNamesLineAndColumn) {
  try {
    parse_csv("x,y\n1,2\n3,abc\n", "curve.csv");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("curve.csv:3"));
    EXPECT_THAT(e.what(), HasSubstr("column 2 ('y')"));
    EXPECT_THAT(e.what(), HasSubstr("'abc'"));
  }
}

TEST(Csv, WrongFieldCountIsRejected) {
  EXPECT_THROW(parse_csv("x,y\n1,2,3\n", "c.csv"), InputError);
  EXPECT_THROW(parse_csv("x,y\n1\n", "c.csv"), InputError);
}

TEST(Csv, MissingHeaderOrColumnIsRejected) {
  EXPECT_THROW(parse_csv("# only a comment\n", "c.csv"), InputError);
  EXPECT_THROW(parse_csv("x,,z\n", "c.csv"), InputError);
  const auto t = parse_csv("x,y\n1,2\n", "c.csv");
  try {
    t.require("force");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no column 'force'"));
    EXPECT_THAT(e.what(), HasSubstr("x, y"));
  }
}

TEST(Csv, UnreadableFileIsAnInputError) {
  EXPECT_THROW(read_csv("/nonexistent/dir/curve.csv"), InputError);
}

}  // namespace
}  // namespace rupture::io

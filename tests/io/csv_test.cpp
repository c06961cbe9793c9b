#include "io/csv.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"

namespace rupture::io {
namespace {

using ::testing::HasSubstr;

TEST(Csv, ParsesCommentsHeaderUnitsAndRows) {
  const auto t =
      parse_csv("# made by hand\n# second\nstrain[%],force [N]\n0,1.5\n0.5, -2e-3\r\n\n1,+3\n", "t.csv");
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

TEST(Csv, UnreadableFileIsAnInputError) { EXPECT_THROW(read_csv("/nonexistent/dir/curve.csv"), InputError); }

// The layouts other tools write.
TEST(Csv, LammpsFixAveTimeHeaderInTheLastCommentLine) {
  const auto t = parse_csv(
      "# Time-averaged data for fix strain_force\n# TimeStep v_strain v_force c_pe\n1000 0.001 2.5 0.1\n2000 "
      "0.002 "
      "4.5e0 0.3\n",
      "log.ave");
  ASSERT_EQ(t.header.size(), 4u);
  EXPECT_EQ(t.header[1], "v_strain");
  EXPECT_EQ(t.comments.size(), 1u);
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_DOUBLE_EQ(t.column("v_force")[1], 4.5);
  EXPECT_EQ(t.line_of_row[0], 3u);
}

TEST(Csv, YadeSaveDataTxtTabsAndPandasIndexAndByteOrderMark) {
  const auto yade = parse_csv("# i\tstrain\tforce\n0\t0\t0\n1\t0.1\t2\n", "yade.txt");
  EXPECT_EQ(yade.header, (std::vector<std::string>{"i", "strain", "force"}));
  EXPECT_DOUBLE_EQ(yade.column("force")[1], 2.0);
  const auto pandas = parse_csv(",strain,force\n0,0.0,0.0\n1,0.1,2.0\n", "df.csv");
  EXPECT_EQ(pandas.header, (std::vector<std::string>{"index", "strain", "force"}));
  const auto bom = parse_csv("\xEF\xBB\xBFstrain[%],force[N]\n0,1\n", "excel.csv");
  EXPECT_EQ(column_name(bom.header[0]), "strain");
  EXPECT_EQ(column_unit(bom.header[0]), "%");
  const auto spaces = parse_csv("strain force\n0   1\n0.5\t2\n", "plain.dat");
  EXPECT_DOUBLE_EQ(spaces.column("force")[1], 2.0);
}

TEST(Csv, TwoColumnsOfOneNameAreRefused) {
  try {
    parse_csv("strain[%],force[N],strain[1]\n0,1,0\n", "dup.csv");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("dup.csv:1"));
    EXPECT_THAT(e.what(), HasSubstr("columns 1 and 3 are both called 'strain'"));
  }
}

TEST(Csv, QuotedInputInMessagesIsCapped) {
  try {
    parse_csv("x,y\n1," + std::string(500, 'z') + "\n", "long.csv");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_LT(std::string(e.what()).size(), 300u) << e.what();
    EXPECT_THAT(e.what(), HasSubstr("zzz..."));
  }
}

}  // namespace
}  // namespace rupture::io

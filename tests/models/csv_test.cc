// Tests of the strict CSV reader: provenance, typed columns, and one-line errors naming file, line and column.
#include "models/core/csv.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "test_util.h"

namespace waam {
namespace {
using ::testing::HasSubstr;

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError thrown)";
}

TEST(CsvTableTest, KeepsProvenanceAndReadsTypedColumns) {
  const CsvTable t = CsvTable::Parse("# Source: somewhere\n#  second line\nno, speed ,name\n1,300,a\n\n2, 600 ,b\n",
                                     "mem.csv");
  EXPECT_EQ(t.provenance(), (std::vector<std::string>{"Source: somewhere", "second line"}));
  EXPECT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.Numbers("speed"), (std::vector<double>{300, 600}));
  EXPECT_EQ(t.Strings("name"), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(t.line(1), 6) << "line numbers count comment and blank lines";
}

TEST(CsvTableTest, ReadsTheSharedTables) {
  const CsvTable t = CsvTable::Read(waam::testing::ModelsData("dai2020_csw_table1.csv"));
  EXPECT_EQ(t.rows(), 12u);
  EXPECT_THAT(t.provenance().front(), HasSubstr("Dai"));
}

TEST(CsvTableTest, TextInANumberNamesFileLineAndColumn) {
  const CsvTable t = CsvTable::Parse("a,b\n1,2\n3,abc\n", "data.csv");
  EXPECT_EQ(ErrorOf([&] { t.Numbers("b"); }), "data.csv:3: column 'b': 'abc' is not a number");
}

// A cell holding a carriage return, a NUL and a tab is quoted back with them escaped (waam::InputError), so the
// message stays one line and cannot rewrite the terminal.
TEST(CsvTableTest, ControlCharactersInAQuotedCellAreEscaped) {
  const CsvTable t = CsvTable::Parse(std::string("a,b\n1,2\r3\0\t4\x7f\n", 14), "data.csv");
  EXPECT_EQ(ErrorOf([&] { t.Numbers("b"); }), "data.csv:2: column 'b': '2\\r3\\x00\\t4\\x7f' is not a number");
}

TEST(CsvTableTest, NanEmptyAndInfinityAreRejected) {
  const CsvTable t = CsvTable::Parse("a,b,c\nnan,,inf\n", "x.csv");
  EXPECT_THAT(ErrorOf([&] { t.Numbers("a"); }), HasSubstr("x.csv:2: column 'a': 'nan' is not a number"));
  EXPECT_THAT(ErrorOf([&] { t.Numbers("b"); }), HasSubstr("x.csv:2: column 'b': '' is not a number (empty cell)"));
  EXPECT_THAT(ErrorOf([&] { t.Numbers("c"); }), HasSubstr("x.csv:2: column 'c': 'inf' is not a number"));
  EXPECT_TRUE(std::isinf(t.Numbers("c", /*allow_infinity=*/true)[0])) << "a straight path's radius may be inf";
}

TEST(CsvTableTest, MissingColumnListsTheColumns) {
  const CsvTable t = CsvTable::Parse("speed,width\n1,2\n", "beads.csv");
  EXPECT_EQ(ErrorOf([&] { t.Numbers("height"); }), "beads.csv: no column 'height' (columns: speed, width)");
}

TEST(CsvTableTest, RaggedRowAndEmptyFileAreErrors) {
  EXPECT_EQ(ErrorOf([] { CsvTable::Parse("a,b\n1,2,3\n", "r.csv"); }), "r.csv:2: 3 fields, but the header has 2");
  EXPECT_THAT(ErrorOf([] { CsvTable::Parse("# only a comment\n", "e.csv"); }), HasSubstr("e.csv: no header row"));
  EXPECT_THAT(ErrorOf([] { CsvTable::Parse("a,a\n", "d.csv"); }), HasSubstr("'a' appears twice"));
  EXPECT_THAT(ErrorOf([] { CsvTable::Read("/nonexistent/waam.csv"); }), HasSubstr("/nonexistent/waam.csv"));
}

}  // namespace
}  // namespace waam

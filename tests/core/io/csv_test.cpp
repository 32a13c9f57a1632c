#include "palpa/io/csv.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include <unistd.h>

namespace palpa::io {
namespace {

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("palpa-csv-" + std::to_string(::getpid()) + "-" + name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string error_of(const std::filesystem::path& p) {
  try {
    (void)read_numeric_csv(p, {"u", "v"});
  } catch (const CsvError& e) {
    return e.what();
  }
  return "";
}

TEST(Csv, ReadsNumbersWithCrlfAndBlankLines) {
  const auto t = read_numeric_csv(write("ok.csv", "u,v\r\n0,1\r\n\r\n0.25, 5e-1\n"), {"u", "v"});
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[1][0], 0.25);
  EXPECT_EQ(t.rows[1][1], 0.5);
  EXPECT_EQ(t.line_numbers[1], 4u);
}

TEST(Csv, ErrorsNameTheFileTheLineAndTheColumn) {
  EXPECT_NE(error_of(write("hdr.csv", "x,y\n0,0\n")).find("header"), std::string::npos);
  const auto bad = error_of(write("bad.csv", "u,v\n0,0\n0,abc\n"));
  EXPECT_NE(bad.find("-bad.csv: line 3: column v"), std::string::npos) << bad;
  EXPECT_NE(error_of(write("count.csv", "u,v\n0,0,0\n")).find("expected 2 values"), std::string::npos);
  EXPECT_NE(error_of(write("inf.csv", "u,v\ninf,0\n")).find("finite"), std::string::npos);
  EXPECT_NE(error_of(write("empty.csv", "")).find("empty"), std::string::npos);
  EXPECT_NE(error_of("/nonexistent/uv.csv").find("no such file"), std::string::npos);
  EXPECT_NE(error_of("/dev/zero").find("not a regular file"), std::string::npos);  // never read forever
}

}  // namespace
}  // namespace palpa::io

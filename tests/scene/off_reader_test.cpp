// Geomview OFF files: every header variant, comments, fan splitting, and errors in the OFF file.
#include "scene/off_reader.h"

#include <gtest/gtest.h>

#include <string>

namespace rad {
namespace {

const char* kSquareVertices =
    "0 0 0\n"
    "1 0 0\n"
    "1 1 0\n"
    "0 1 0\n";

Error off_error(std::string_view text) {
  try {
    parse_off_text(text, "m.off");
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return Error("none");
}

void expect_off_error(std::string_view text, int line, int column, const std::string& substring) {
  Error e = off_error(text);
  EXPECT_EQ(e.loc().file, "m.off");
  EXPECT_EQ(e.loc().line, line) << e.what();
  EXPECT_EQ(e.loc().column, column) << e.what();
  EXPECT_NE(e.message().find(substring), std::string::npos) << e.what();
}

TEST(OffReader, ReadsPlainOff) {
  OffTriangles m = parse_off_text("OFF\n3 1 3\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "m.off");
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.vertex_count, 3u);
  EXPECT_EQ(m.face_count, 1u);
  EXPECT_EQ(m.triangles[0][1], Vec3(1, 0, 0));
  EXPECT_EQ(m.triangles[0][2], Vec3(0, 1, 0));
}

TEST(OffReader, SplitsFacesIntoFans) {
  OffTriangles m = parse_off_text(
      std::string("OFF\n5 1 0\n") + kSquareVertices + "0.5 1.5 0\n5 0 1 2 4 3\n", "m.off");
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.triangles[0][0], Vec3(0, 0, 0));
  EXPECT_EQ(m.triangles[0][1], Vec3(1, 0, 0));
  EXPECT_EQ(m.triangles[0][2], Vec3(1, 1, 0));
  EXPECT_EQ(m.triangles[1][0], Vec3(0, 0, 0));
  EXPECT_EQ(m.triangles[1][1], Vec3(1, 1, 0));
  EXPECT_EQ(m.triangles[1][2], Vec3(0.5f, 1.5f, 0));
  EXPECT_EQ(m.triangles[2][2], Vec3(0, 1, 0));
}

TEST(OffReader, LocatesEveryTriangleAtItsFaceLine) {
  OffTriangles m = parse_off_text(
      std::string("OFF\n4 2 0\n") + kSquareVertices + "3 0 1 2\n  4 0 1 2 3\n", "m.off");
  ASSERT_EQ(m.triangle_locs.size(), 3u);
  EXPECT_EQ(m.triangle_locs[0].file, "m.off");
  EXPECT_EQ(m.triangle_locs[0].line, 7);
  EXPECT_EQ(m.triangle_locs[0].column, 1);
  EXPECT_EQ(m.triangle_locs[1].line, 8);
  EXPECT_EQ(m.triangle_locs[1].column, 3);
  EXPECT_EQ(m.triangle_locs[2].line, 8);
}

TEST(OffReader, IgnoresVertexColoursOfCoff) {
  OffTriangles m = parse_off_text(
      "COFF\n3 1 0\n0 0 0 1 0 0 1\n2 0 0 0 1 0 1\n0 3 0 0 0 1 0.5\n3 0 1 2\n", "m.off");
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0][1], Vec3(2, 0, 0));
  EXPECT_EQ(m.triangles[0][2], Vec3(0, 3, 0));
}

TEST(OffReader, IgnoresVertexNormalsOfNoff) {
  OffTriangles m =
      parse_off_text("NOFF\n3 1 0\n0 0 0 0 0 1\n2 0 0 0 0 1\n0 3 0 0 0 1\n3 0 1 2\n", "m.off");
  EXPECT_EQ(m.triangles[0][1], Vec3(2, 0, 0));
}

TEST(OffReader, IgnoresNormalsAndColoursOfNcoffAndCnoff) {
  for (const char* header : {"NCOFF", "CNOFF"}) {
    OffTriangles m = parse_off_text(std::string(header) +
                                        "\n3 1 0\n0 0 0 0 0 1 1 1 1 1\n2 0 0 0 0 1 1 1 1 1\n"
                                        "0 3 0 0 0 1 1 1 1 1\n3 0 1 2\n",
                                    "m.off");
    EXPECT_EQ(m.triangles[0][2], Vec3(0, 3, 0)) << header;
  }
}

TEST(OffReader, AcceptsTextureCoordinateHeader) {
  OffTriangles m =
      parse_off_text("STOFF\n3 1 0\n0 0 0 0 0\n2 0 0 1 0\n0 3 0 0 1\n3 0 1 2\n", "m.off");
  EXPECT_EQ(m.triangles[0][1], Vec3(2, 0, 0));
}

TEST(OffReader, ReadsFileWithoutHeaderKeyword) {
  OffTriangles m = parse_off_text("3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "m.off");
  EXPECT_EQ(m.triangles.size(), 1u);
}

TEST(OffReader, ReadsCountsOnTheHeaderLine) {
  OffTriangles m = parse_off_text("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "m.off");
  EXPECT_EQ(m.triangles.size(), 1u);
}

TEST(OffReader, IgnoresPerFaceColours) {
  OffTriangles m = parse_off_text(
      std::string("OFF\n4 2 0\n") + kSquareVertices + "3 0 1 2 1 0 0\n3 0 2 3 0.5 0.5 0.5 1\n",
      "m.off");
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[1][2], Vec3(0, 1, 0));
}

TEST(OffReader, SkipsCommentsBlankLinesAndCrLf) {
  OffTriangles m = parse_off_text(
      "# a comment\r\n\r\nOFF # header\r\n# counts next\r\n3 1 0\r\n0 0 0\r\n\r\n1 0 0 # x\r\n"
      "0 1 0\r\n3 0 1 2\r\n",
      "m.off");
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangle_locs[0].line, 10);
}

TEST(OffReader, ReadsCLikeNumbers) {
  OffTriangles m = parse_off_text("OFF\n3 1 0\n.5 -0 +0\n1e1 0. 0\n0 2.5E-1 0\n3 0 1 2\n", "m.off");
  EXPECT_EQ(m.triangles[0][0], Vec3(0.5f, 0, 0));
  EXPECT_EQ(m.triangles[0][1], Vec3(10, 0, 0));
  EXPECT_EQ(m.triangles[0][2], Vec3(0, 0.25f, 0));
}

TEST(OffReader, ReportsOutOfRangeIndexAtTheIndex) {
  expect_off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 3 2\n", 6, 5, "out of range [0, 3)");
  expect_off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 6, 5, "out of range");
}

TEST(OffReader, ReportsFileWithoutFacesAtTheFaceCount) {
  expect_off_error("OFF\n3  0 0\n0 0 0\n1 0 0\n0 1 0\n", 2, 4, "no faces");
}

TEST(OffReader, ReportsFaceWithFewerThanThreeVertices) {
  expect_off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 6, 1, "at least 3 vertices");
}

TEST(OffReader, ReportsFaceWithMissingIndices) {
  expect_off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", 6, 7, "only 3 indices");
}

TEST(OffReader, ReportsNonIntegerIndex) {
  expect_off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", 6, 5,
                   "expected a vertex index but found '1.5'");
}

TEST(OffReader, ReportsMissingVertexLinesAtEndOfFile) {
  expect_off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n", 5, 1,
                   "unexpected end of file: expected vertex 2 of 3");
}

TEST(OffReader, ReportsMissingFacesAtEndOfFile) {
  expect_off_error("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2", 6, 8,
                   "unexpected end of file: expected face 1 of 2");
}

TEST(OffReader, ReportsEmptyFile) {
  expect_off_error("# nothing\n", 2, 1, "unexpected end of file");
}

TEST(OffReader, ReportsShortVertexLine) {
  expect_off_error("OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 4, 3,
                   "expected 3 vertex coordinates");
}

TEST(OffReader, ReportsNonFiniteCoordinate) {
  expect_off_error("OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", 4, 3, "non-finite number 'inf'");
}

TEST(OffReader, ReportsBadCounts) {
  expect_off_error("OFF\n3 x 0\n", 2, 3, "expected a count");
  expect_off_error("OFF\n-3 1 0\n", 2, 1, "expected a count");
  expect_off_error("OFF\n3\n", 2, 1, "expected the vertex and face counts");
}

TEST(OffReader, ReportsUnknownHeader) {
  expect_off_error("PLY\n3 1 0\n", 1, 1, "expected an OFF header");
  expect_off_error("XOFF\n3 1 0\n", 1, 1, "unknown OFF header 'XOFF'");
  expect_off_error("CCOFF\n3 1 0\n", 1, 1, "unknown OFF header");
}

TEST(OffReader, RejectsFourDimensionalAndBinaryVariants) {
  expect_off_error("4OFF\n3 1 0\n", 1, 1, "unsupported OFF variant '4OFF'");
  expect_off_error("nOFF\n4\n3 1 0\n", 1, 1, "unsupported OFF variant");
  expect_off_error("OFF BINARY\n", 1, 5, "binary OFF");
}

TEST(OffReader, ReportsMissingFileAtTheRequestingToken) {
  SourceLoc from{"scene.des", 4, 12};
  try {
    read_off_file("/nonexistent/x.off", from);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().file, "scene.des");
    EXPECT_EQ(e.loc().line, 4);
    EXPECT_EQ(e.loc().column, 12);
    EXPECT_NE(e.message().find("cannot open '/nonexistent/x.off'"), std::string::npos);
  }
}

}  // namespace
}  // namespace rad

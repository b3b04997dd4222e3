// IES LM-63 files: a known distribution read back within 0.5% between its angles, every
// horizontal symmetry, the header variants of 1986 to 2002, the factors and lumens, each
// malformed case as one error at its file:line, and a light's candela toward a direction.
#include "scene/ies_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "scene/light.h"
#include "scene/photometry.h"

namespace rad {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::string join(const std::vector<double>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? " " : "") + std::to_string(v[i]);
  return s;
}

// An LM-63-2002 file of the given angles and candela f(gamma, c), with the given multiplier and
// ballast factor (lamps 1, 1000 lm).
std::string ies_text(const std::vector<double>& vertical, const std::vector<double>& horizontal,
                     const std::function<double(double, double)>& f, double multiplier = 1.0,
                     double ballast = 1.0) {
  std::string s = "IESNA:LM-63-2002\n[TEST] rad\n[MANUFAC] none\nTILT=NONE\n";
  s += "1 1000 " + std::to_string(multiplier) + " " + std::to_string(vertical.size()) + " " +
       std::to_string(horizontal.size()) + " 1 2 0.1 0.1 0\n";
  s += std::to_string(ballast) + " 1 20\n";
  s += join(vertical) + "\n" + join(horizontal) + "\n";
  for (double c : horizontal) {
    std::vector<double> row;
    for (double g : vertical) row.push_back(f(g, c));
    s += join(row) + "\n";
  }
  return s;
}

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> v;
  for (double x = from; x <= to + 1e-9; x += step) v.push_back(x);
  return v;
}

TEST(IesReader, AKnownDistributionIsReadBackWithinHalfAPercentBetweenItsAngles) {
  // A cosine (Lambertian) downlight of 1000 cd at the nadir, every 5 degrees, times a
  // multiplier of 2 and a ballast factor of 0.9.
  const auto cosine = [](double g, double) { return 1000.0 * std::max(0.0, std::cos(g * kDeg)); };
  const Photometry p = parse_ies(ies_text(steps(0, 90, 5), {0}, cosine, 2.0, 0.9), "down.ies");
  EXPECT_EQ(p.symmetry, CSymmetry::Rotational);
  EXPECT_EQ(p.lumens(), 1000.0f);
  EXPECT_FLOAT_EQ(p.multiplier, 2.0f);
  EXPECT_FLOAT_EQ(p.ballast_factor, 0.9f);
  EXPECT_FLOAT_EQ(p.input_watts, 20.0f);
  EXPECT_FLOAT_EQ(p.max_candela, 1800.0f);
  for (double g : {0.0, 2.5, 12.5, 37.5, 44.0, 62.5, 80.0, 87.5}) {
    for (double c : {0.0, 33.0, 190.0, -45.0}) {
      const double want = 1800.0 * std::cos(g * kDeg);
      EXPECT_NEAR(p.candela_at(float(g), float(c)), want, 0.005 * want) << g << " " << c;
    }
  }
  EXPECT_EQ(p.candela_at(90.0f, 0.0f), 0.0f);
  EXPECT_EQ(p.candela_at(120.0f, 0.0f), 0.0f);  // beyond the file's vertical angles
  // Its flux: pi times the peak for a cosine distribution.
  EXPECT_NEAR(p.flux(), std::numbers::pi * 1800.0, 0.005 * std::numbers::pi * 1800.0);
}

TEST(IesReader, TheTableIsBilinearBetweenItsAngles) {
  const auto f = [](double g, double c) { return 10.0 + g + 0.5 * c + 0.01 * g * c; };
  const Photometry p = parse_ies(ies_text({0, 30, 90, 180}, {0, 45, 200, 360}, f), "full.ies");
  EXPECT_EQ(p.symmetry, CSymmetry::Full);
  for (double g : {0.0, 10.0, 29.0, 60.0, 100.0, 179.0}) {
    for (double c : {0.0, 20.0, 44.0, 120.0, 300.0, 359.0}) {
      EXPECT_NEAR(p.candela_at(float(g), float(c)), f(g, c), 1e-3 * f(g, c)) << g << " " << c;
    }
  }
  EXPECT_NEAR(p.candela_at(60.0f, 380.0f), f(60, 20), 1e-3 * f(60, 20));  // modulo 360
}

TEST(IesReader, EachHorizontalSymmetryFoldsTheCirclesOtherParts) {
  const auto f = [](double g, double c) { return 100.0 + g + c; };
  const std::vector<double> v = steps(0, 180, 10);
  struct Case {
    std::vector<double> h;
    CSymmetry symmetry;
    std::vector<std::pair<double, double>> same;  // (C asked, C of the file it equals)
  };
  const Case cases[] = {
      {{0}, CSymmetry::Rotational, {{0, 0}, {123, 0}, {359, 0}}},
      {steps(0, 90, 15), CSymmetry::Quadrant, {{60, 60}, {120, 60}, {210, 30}, {300, 60}}},
      {steps(0, 180, 15), CSymmetry::Bilateral, {{150, 150}, {200, 160}, {270, 90}, {345, 15}}},
      {steps(90, 270, 15), CSymmetry::Bilateral90, {{180, 180}, {45, 135}, {300, 240}, {0, 180}}},
      {steps(0, 360, 15), CSymmetry::Full, {{200, 200}, {350, 350}}},
  };
  for (const Case& k : cases) {
    const Photometry p = parse_ies(ies_text(v, k.h, f), "sym.ies");
    EXPECT_EQ(p.symmetry, k.symmetry) << to_string(k.symmetry);
    for (const auto& [asked, in_file] : k.same) {
      const double want = k.h.size() == 1 ? f(40, 0) : f(40, in_file);
      EXPECT_NEAR(p.candela_at(40.0f, float(asked)), want, 1e-3 * want)
          << to_string(k.symmetry) << " C " << asked;
    }
  }
}

TEST(IesReader, ReadsEveryHeaderVariantCommasCrLfAndTiltInclude) {
  const std::string numbers = "2 -1 1 3 1 1 1 0 0 0\n1.0 1.0 50\n0 45 90\n0\n300 200 100\n";
  // LM-63-1986: free text, no IESNA line. -1 lumens: absolute photometry.
  const Photometry a = parse_ies("Some lamp maker\nCatalog 12\nTILT=NONE\n" + numbers, "a.ies");
  EXPECT_LT(a.lumens(), 0.0f);
  EXPECT_EQ(a.lamps, 2);
  EXPECT_FLOAT_EQ(a.candela_at(45.0f, 0.0f), 200.0f);
  // LM-63-1991 with keywords, CR LF line ends and commas between the numbers.
  std::string crlf = "IESNA91\r\n[TEST] x\r\n[MORE] y\r\nTILT=NONE\r\n" + numbers;
  for (size_t i = 0; (i = crlf.find('\n', i)) != std::string::npos; i += 2) {
    if (crlf[i - 1] != '\r') crlf.insert(i, "\r");
  }
  const Photometry b = parse_ies(crlf, "b.ies");
  EXPECT_FLOAT_EQ(b.candela_at(22.5f, 0.0f), 250.0f);
  const Photometry c = parse_ies(
      "IESNA:LM-63-1995\nTILT=NONE\n2,-1,1,3,1,1,1,0,0,0\n1,1,50\n0,45,90\n0\n300,200,100\n",
      "c.ies");
  EXPECT_FLOAT_EQ(c.candela_at(90.0f, 0.0f), 100.0f);
  // TILT=INCLUDE: the tilt table is read past (with a warning), the photometry read as usual.
  const Photometry d =
      parse_ies("IESNA:LM-63-2002\nTILT=INCLUDE\n1\n3\n0 45 90\n1 0.9 0.8\n" + numbers, "d.ies");
  EXPECT_FLOAT_EQ(d.candela_at(0.0f, 0.0f), 300.0f);
  // An uplight, vertical angles 90 to 180: nothing below the horizon.
  const Photometry e = parse_ies(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 1 2 0 0 0\n1 1 10\n90 180\n0\n50 150\n", "e.ies");
  EXPECT_EQ(e.candela_at(45.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(e.candela_at(135.0f, 0.0f), 100.0f);
}

// parse_ies refuses `text` with one error at `line` (and `column` when not 0) saying `what`.
void expect_refused(const std::string& text, int line, int column, const std::string& what) {
  try {
    parse_ies(text, "bad.ies");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().file, "bad.ies");
    EXPECT_EQ(e.loc().line, line) << e.what();
    if (column) {
      EXPECT_EQ(e.loc().column, column) << e.what();
    }
    EXPECT_NE(e.message().find(what), std::string::npos) << e.what();
  }
}

TEST(IesReader, EachMalformedFileEndsInOneErrorAtItsLine) {
  const std::string head = "IESNA:LM-63-2002\n[TEST] t\nTILT=NONE\n";  // lines 1-3
  const std::string counts = "1 1000 1 3 2 1 2 0 0 0\n1 1 10\n";       // lines 4-5
  const std::string angles = "0 45 90\n0 90\n";                        // lines 6-7
  const std::string good = head + counts + angles + "100 50 0\n100 40 0\n";
  ASSERT_NO_THROW(parse_ies(good, "good.ies"));
  expect_refused("", 1, 1, "no TILT= line");
  expect_refused("IESNA:LM-63-2002\n1 1000 1 3 2 1 2 0 0 0\n", 1, 1, "no TILT= line");
  // Non-numeric and non-finite values, where they are.
  expect_refused(head + counts + angles + "100 fifty 0\n100 40 0\n", 8, 5,
                 "'fifty' is not a number");
  expect_refused(head + counts + angles + "100 50 0\n100 nan 0\n", 9, 5, "not a finite number");
  expect_refused(head + "1 1000 1 three 2 1 2 0 0 0\n", 4, 10, "'three' is not a number");
  // Truncated: the table ends early; the header ends early.
  expect_refused(head + counts + angles + "100 50 0\n100 40\n", 9, 7, "unexpected end of file");
  expect_refused(head + "1 1000 1 3\n", 4, 11, "unexpected end of file");
  // Wrong counts: more values than the counts make, or counts out of range.
  expect_refused(good + "7\n", 10, 1, "after the candela table");
  expect_refused(head + "1 1000 1 3 2.5 1 2 0 0 0\n", 4, 12, "whole number");
  expect_refused(head + "1 1000 1 1 1 1 2 0 0 0\n", 4, 10, "number of vertical angles");
  expect_refused(head + "1 1000 1 3 99999999 1 2 0 0 0\n", 4, 12, "number of horizontal angles");
  // Angles out of order, out of type C's range, or horizontals of no symmetry.
  expect_refused(head + counts + "0 90 45\n0 90\n", 6, 6, "does not increase");
  expect_refused(head + counts + "0 45 90\n90 0\n", 7, 4, "does not increase");
  expect_refused(head + counts + "0 45 190\n0 90\n", 6, 6, "outside 0 to 180");
  expect_refused(head + counts + "0 45 90\n0 270\n", 7, 1, "0 to 90, 0 to 180, 90 to 270");
  // Photometry types A and B, a negative candela, a zero multiplier.
  expect_refused(head + "1 1000 1 3 2 2 2 0 0 0\n", 4, 14, "type B");
  expect_refused(head + "1 1000 1 3 2 3 2 0 0 0\n", 4, 14, "type A");
  expect_refused(head + counts + angles + "100 -50 0\n100 40 0\n", 8, 5, "negative candela");
  expect_refused(head + "1 1000 0 3 2 1 2 0 0 0\n", 4, 8, "candela multiplier");
  expect_refused(head + "1 0 1 3 2 1 2 0 0 0\n", 4, 3, "lumens per lamp");
}

TEST(IesReader, AMissingFileIsReportedWhereItWasNamed) {
  try {
    read_ies_file("/nonexistent/lamp.ies", SourceLoc{"scene.des", 4, 20});
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 4);
    EXPECT_EQ(e.loc().column, 20);
  }
}

TEST(IesReader, ALightWithPhotometryTakesItsTableTowardEachDirection) {
  // Bilateral: brighter toward C90 than C0. The light hangs pointing down (-y), C0 along +x,
  // so C90 = C0 x direction = -z.
  const auto f = [](double g, double c) { return (100.0 + c) * std::cos(g * kDeg * 0.5); };
  auto p = std::make_shared<const Photometry>(
      parse_ies(ies_text(steps(0, 180, 5), steps(0, 180, 10), f), "bi.ies"));
  Light l;
  l.kind = LightKind::Point;
  l.direction = Vec3(0, -1, 0);
  l.photometric_up = Vec3(1, 0, 0);
  l.photometry = p;
  l.intensity = 2.0f;  // a multiplier on the table
  EXPECT_NO_THROW(check_light(l));
  auto toward = [](double gamma, const Vec3& across) {
    return glm::normalize(Vec3(0, -1, 0) * float(std::cos(gamma * kDeg)) +
                          across * float(std::sin(gamma * kDeg)));
  };
  EXPECT_NEAR(intensity_toward(l, Vec3(0, -1, 0)), 2 * f(0, 0), 1e-3);
  EXPECT_NEAR(intensity_toward(l, toward(30, Vec3(1, 0, 0))), 2 * f(30, 0), 1e-2);
  EXPECT_NEAR(intensity_toward(l, toward(30, Vec3(0, 0, -1))), 2 * f(30, 90), 1e-2);
  EXPECT_NEAR(intensity_toward(l, toward(30, Vec3(0, 0, 1))), 2 * f(30, 90), 1e-2);  // C270
  EXPECT_NEAR(intensity_toward(l, toward(30, Vec3(-1, 0, 0))), 2 * f(30, 180), 1e-2);
  EXPECT_NEAR(intensity_toward(l, Vec3(0, 1, 0)), 2 * f(180, 0), 1e-2);
  // As a spot, the cone's falloff on top of the table.
  l.kind = LightKind::Spot;
  l.inner_cone = float(10 * kDeg), l.outer_cone = float(20 * kDeg);
  EXPECT_NEAR(intensity_toward(l, toward(5, Vec3(1, 0, 0))), 2 * f(5, 0), 1e-2);
  EXPECT_EQ(intensity_toward(l, toward(30, Vec3(1, 0, 0))), 0.0f);
}

}  // namespace
}  // namespace rad

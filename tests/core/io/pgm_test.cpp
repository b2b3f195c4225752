#include "core/io/pgm.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/core/io/temp_dir.hpp"

namespace irgs {
namespace {

std::string firstError(const PgmReadResult& r) {
  for (const auto& d : r.diagnostics) {
    if (d.severity == Severity::kError)
      return d.toString();
  }
  return {};
}

TEST(Pgm, ReadsBinaryP5WithCommentsInTheHeader) {
  const std::string bytes = std::string("P5\n# made by hand\n3 # width\n2\n255\n") +
                            std::string("\x00\x10\x20\x30\x40\xff", 6);
  const PgmReadResult r = parsePgm(bytes, "a.pgm");
  ASSERT_TRUE(r.image) << firstError(r);
  EXPECT_EQ(r.image->width, 3);
  EXPECT_EQ(r.image->height, 2);
  EXPECT_EQ(r.image->pixels, (std::vector<std::uint8_t>{0x00, 0x10, 0x20, 0x30, 0x40, 0xff}));
  EXPECT_TRUE(r.diagnostics.empty());
}

TEST(Pgm, ReadsPlainP2AndScalesMaxvalTo8Bit) {
  // maxval 15: 15 -> 255, 8 -> round(8 * 255 / 15) = 136, 1 -> 17.
  const PgmReadResult r = parsePgm("P2 2 2 15\n0 15\n# a comment between samples\n8\t1\n", "b");
  ASSERT_TRUE(r.image) << firstError(r);
  EXPECT_EQ(r.image->pixels, (std::vector<std::uint8_t>{0, 255, 136, 17}));
}

TEST(Pgm, Reads16BitBigEndianP5) {
  // maxval 65535: 0xFFFF -> 255, 0x8000 -> round(32768 * 255 / 65535) = 128, 0x0101 -> 1.
  const std::string bytes =
      std::string("P5 3 1 65535\n") + std::string("\xff\xff\x80\x00\x01\x01", 6);
  const PgmReadResult r = parsePgm(bytes, "c");
  ASSERT_TRUE(r.image) << firstError(r);
  EXPECT_EQ(r.image->pixels, (std::vector<std::uint8_t>{255, 128, 1}));
}

TEST(Pgm, WriteThenReadGivesTheSameImage) {
  test::TempDir dir;
  GrayImage image;
  image.width = 17;
  image.height = 5;
  std::mt19937 rng(42);
  for (int i = 0; i < image.width * image.height; ++i)
    image.pixels.push_back(static_cast<std::uint8_t>(rng() & 0xFF));
  ASSERT_EQ(writePgmFile(image, dir / "x.pgm", "line one\nline two"), std::nullopt);
  const PgmReadResult r = readPgmFile(dir / "x.pgm");
  ASSERT_TRUE(r.image) << firstError(r);
  EXPECT_EQ(r.image->width, 17);
  EXPECT_EQ(r.image->height, 5);
  EXPECT_EQ(r.image->pixels, image.pixels);
}

TEST(Pgm, TruncatedBinaryDataIsAnErrorThatGivesTheSizes) {
  const PgmReadResult r = parsePgm(std::string("P5 4 4 255\n") + std::string(10, 'a'), "t.pgm");
  EXPECT_FALSE(r.image);
  const std::string e = firstError(r);
  EXPECT_NE(e.find("t.pgm"), std::string::npos) << e;
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  EXPECT_NE(e.find("16"), std::string::npos) << e;
  EXPECT_NE(e.find("10"), std::string::npos) << e;
}

TEST(Pgm, TruncatedPlainDataIsAnError) {
  const PgmReadResult r = parsePgm("P2\n2 2\n255\n1 2 3", "t");
  EXPECT_FALSE(r.image);
  EXPECT_NE(firstError(r).find("truncated"), std::string::npos) << firstError(r);
}

TEST(Pgm, HeaderErrorsAreLocatedByLineAndColumn) {
  const PgmReadResult r = parsePgm("P5\n# c\n12 x\n255\n", "h.pgm");
  ASSERT_FALSE(r.image);
  ASSERT_EQ(r.diagnostics.size(), 1U);
  EXPECT_EQ(r.diagnostics[0].line, 3);
  EXPECT_EQ(r.diagnostics[0].column, 4);
  EXPECT_NE(r.diagnostics[0].message.find("height"), std::string::npos);
}

TEST(Pgm, RejectsOtherFormatsBadMaxvalAndOutOfRangeSamples) {
  EXPECT_NE(firstError(parsePgm("P6 1 1 255\n\x01\x02\x03", "f")).find("P6"), std::string::npos);
  EXPECT_NE(firstError(parsePgm("GIF89a", "f")).find("not a PGM"), std::string::npos);
  EXPECT_NE(firstError(parsePgm("P5 1 1 70000\n\x01", "f")).find("maxval"), std::string::npos);
  EXPECT_NE(firstError(parsePgm("P5 1 1 0\n\x01", "f")).find("maxval"), std::string::npos);
  EXPECT_NE(firstError(parsePgm("P5 0 1 255\n", "f")).find("width"), std::string::npos);
  EXPECT_NE(firstError(parsePgm("P2 1 1 10\n11\n", "f")).find("exceeds maxval"), std::string::npos);
  EXPECT_NE(firstError(parsePgm("P5 1 1 100\n\xff", "f")).find("exceeds maxval"),
            std::string::npos);
  EXPECT_NE(firstError(parsePgm("P5 99999999999 1 255\n", "f")).find("width"), std::string::npos);
  EXPECT_NE(firstError(parsePgm("P5 1 1 255", "f")).find("no pixel data"), std::string::npos);
}

TEST(Pgm, HugeDeclaredSizeIsRejectedWithoutAllocating) {
  const PgmReadResult r = parsePgm("P2 2000000000 2000000000 255\n1 2 3\n", "big");
  EXPECT_FALSE(r.image);
  EXPECT_NE(firstError(r).find("truncated"), std::string::npos);
}

TEST(Pgm, MissingFileIsADiagnostic) {
  test::TempDir dir;
  const PgmReadResult r = readPgmFile(dir / "nope.pgm");
  EXPECT_FALSE(r.image);
  EXPECT_NE(firstError(r).find("nope.pgm"), std::string::npos);
}

TEST(Pgm, RandomMutationsNeverCrashAndErrorsNeverCarryAnImage) {
  GrayImage image{6, 4, std::vector<std::uint8_t>(24, 7)};
  const std::string p5 = encodePgm(image, "x");
  const std::string p2 = "P2\n# c\n3 2\n300\n0 1 2\n299 300 5\n";
  std::mt19937 rng(1234);
  for (int i = 0; i < 4000; ++i) {
    std::string bytes = i % 2 == 0 ? p5 : p2;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !bytes.empty(); ++e) {
      const std::size_t at = rng() % bytes.size();
      switch (rng() % 3) {
        case 0:
          bytes[at] = static_cast<char>(rng() & 0xFF);
          break;
        case 1:
          bytes.erase(at, 1);
          break;
        default:
          bytes.resize(at);
          break;
      }
    }
    const PgmReadResult r = parsePgm(bytes, "m");
    EXPECT_EQ(r.image.has_value(), !hasErrors(r.diagnostics));
    if (r.image) {
      EXPECT_EQ(r.image->pixels.size(), static_cast<std::size_t>(r.image->width) *
                                            static_cast<std::size_t>(r.image->height));
    }
  }
}

}  // namespace
}  // namespace irgs

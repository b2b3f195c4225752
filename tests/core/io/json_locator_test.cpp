#include "core/io/json_locator.hpp"

#include <gtest/gtest.h>

#include <ostream>

namespace irgs {

void PrintTo(const TextPosition& p, std::ostream* os) {
  *os << p.line << ":" << p.column;
}

namespace {

constexpr const char* kText = R"({
  "name": "x",
  "walls": [
    {"id": "a/b", "points": [[0, 0], [1, 0]]},
    {"id": "c~d",
     "points": []}
  ],
  "é": {"k": true}
})";

TEST(JsonLocator, FindsValuesByPointer) {
  const JsonLocator loc(kText);
  EXPECT_EQ(loc.locate(""), (TextPosition{1, 1}));
  EXPECT_EQ(loc.locate("/name"), (TextPosition{2, 11}));
  EXPECT_EQ(loc.locate("/walls"), (TextPosition{3, 12}));
  EXPECT_EQ(loc.locate("/walls/0"), (TextPosition{4, 5}));
  EXPECT_EQ(loc.locate("/walls/0/points/1"), (TextPosition{4, 38}));
  EXPECT_EQ(loc.locate("/walls/0/points/1/0"), (TextPosition{4, 39}));
  EXPECT_EQ(loc.locate("/walls/1/points"), (TextPosition{6, 16}));
}

TEST(JsonLocator, EscapesSlashAndTildeInKeysAndCountsCharactersNotBytes) {
  const std::string text = R"({"a/b": 1, "c~d": 2, "é": {"k": true}})";
  const JsonLocator loc(text);
  EXPECT_EQ(loc.locate("/a~1b"), (TextPosition{1, 9}));
  EXPECT_EQ(loc.locate("/c~0d"), (TextPosition{1, 19}));
  // "é" is two bytes but one column.
  EXPECT_EQ(loc.locate("/é/k"), (TextPosition{1, 33}));
  EXPECT_EQ(JsonLocator::escapeToken("a/b~c"), "a~1b~0c");
}

TEST(JsonLocator, MissingValuesFallBackToTheirNearestAncestor) {
  const JsonLocator loc(kText);
  EXPECT_EQ(loc.locate("/walls/1/closed"), loc.locate("/walls/1"));
  EXPECT_EQ(loc.locate("/walls/7/points"), loc.locate("/walls"));
  EXPECT_EQ(loc.locate("/nothing"), (TextPosition{1, 1}));
}

TEST(JsonLocator, EscapedKeysAreDecoded) {
  const JsonLocator loc(R"({"a\u0041": [true]})");
  EXPECT_EQ(loc.locate("/aA/0"), (TextPosition{1, 14}));
}

TEST(JsonLocator, DuplicateKeysResolveToTheLastLikeTheParser) {
  const JsonLocator loc("{\"a\": 1,\n\"a\": 2}");
  EXPECT_EQ(loc.locate("/a"), (TextPosition{2, 6}));
}

TEST(JsonLocator, PointerAtNamesTheValueBeingReadAtAnOffset) {
  const std::string text = R"({"walls": [{"points": [[0, 0], [1 0]]}]})";
  const JsonLocator loc(text);
  const std::size_t bad = text.find("0]]");  // the "0" after the missing comma
  EXPECT_EQ(loc.pointerAt(bad), "/walls/0/points/1/0");
  EXPECT_EQ(loc.pointerAt(0), "");
  EXPECT_EQ(loc.pointerAt(text.find("[{")), "/walls");
}

TEST(JsonLocator, PositionOfCountsLinesAndClampsPastTheEnd) {
  const JsonLocator loc("a\nbc\n");
  EXPECT_EQ(loc.positionOf(0), (TextPosition{1, 1}));
  EXPECT_EQ(loc.positionOf(3), (TextPosition{2, 2}));
  EXPECT_EQ(loc.positionOf(5), (TextPosition{3, 1}));
  EXPECT_EQ(loc.positionOf(500), (TextPosition{3, 1}));
}

TEST(JsonLocator, MalformedTextNeverCrashes) {
  for (const char* text : {"", "{", "[", "{\"a\"", "{\"a\":", "]]]", "{\"a\" 1}", "\"unterminated",
                           "{,}", "[1,,2]", "{\"a\":1}}}"}) {
    const JsonLocator loc(text);
    (void)loc.locate("/a/0");
    (void)loc.pointerAt(3);
  }
  SUCCEED();
}

TEST(JsonLocator, StaticHelpersAgreeWithTheLocator) {
  const JsonLocator loc(kText);
  const std::string text = kText;
  for (std::size_t offset : {std::size_t{0}, text.find("points"), text.find("true"), text.size()}) {
    EXPECT_EQ(JsonLocator::positionIn(text, offset), loc.positionOf(offset));
    EXPECT_EQ(JsonLocator::pointerIn(text, offset), loc.pointerAt(offset));
  }
}

TEST(JsonLocator, DeeplyNestedTextIsScannedInLinearTime) {
  // 200k levels: quadratic pointer building would take minutes.
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  const std::string pointer = JsonLocator::pointerIn(deep, 64);
  EXPECT_EQ(pointer.size(), 64U * 2U);  // "/0" per level entered
  EXPECT_EQ(JsonLocator::positionIn(deep, 64), (TextPosition{1, 65}));
}

TEST(JsonLocator, NestingDepthIgnoresBracketsInStrings) {
  EXPECT_EQ(maxNestingDepth(R"({"a": "[[[[", "b": [[1]]})").depth, 3);
  const NestingDepth d = maxNestingDepth("[[[]]]");
  EXPECT_EQ(d.depth, 3);
  EXPECT_EQ(d.offset, 2U);
}

}  // namespace
}  // namespace irgs

#include "mrsv/metadata.h"

#include <gtest/gtest.h>

#include <string>

namespace mrsv {
namespace {

Error parse(const std::string& text, Metadata* out) {
  return parseMetadata(reinterpret_cast<const uint8_t*>(text.data()), text.size(), 100, out);
}

TEST(Metadata, RoundTrip) {
  Metadata m;
  m.set("spacing", "30,30");
  m.set("crs", "EPSG:32610");
  m.set("description", "Mount St. Helens \xE2\x80\x94 after 1980");
  m.set("empty", "");
  std::vector<uint8_t> bytes = serializeMetadata(m);
  Metadata back;
  ASSERT_TRUE(parseMetadata(bytes.data(), bytes.size(), 0, &back).ok());
  EXPECT_EQ(back.entries, m.entries);
}

TEST(Metadata, EmptyPayloadHasNoEntries) {
  Metadata m;
  EXPECT_TRUE(parse("", &m).ok());
  EXPECT_TRUE(m.entries.empty());
}

struct BadCase {
  const char* text;
  uint64_t offset;  // where the error must point (payload starts at 100)
};

TEST(Metadata, RejectsEachBrokenRuleAtTheEntry) {
  const BadCase cases[] = {
      {"a=1", 100},                      // no final LF
      {"a=1\nnoequals\n", 104},          // entry without '='
      {"a=1\na=2\n", 104},               // duplicate key
      {"=1\n", 100},                     // empty key
      {"Upper=1\n", 100},                // key must be lower case
      {"9lives=1\n", 100},               // key must start with a letter
      {"a=\x01\n", 100},                 // control character
      {"a=\xC3\n", 100},                 // truncated UTF-8
      {"a=\xC0\xAF\n", 100},             // overlong UTF-8
      {"a=\xED\xA0\x80\n", 100},         // surrogate
      {"spacing=30,x\n", 100},           // registered number list
      {"origin=1,2,3,4\n", 100},         // more than three numbers
      {"a=1\r\n", 100},                  // CR is a control character
  };
  for (const BadCase& c : cases) {
    Metadata m;
    Error e = parse(c.text, &m);
    EXPECT_EQ(e.status, Status::kBadMetadata) << c.text;
    EXPECT_EQ(e.offset, c.offset) << c.text;
  }
}

TEST(Metadata, KeyLengthLimit) {
  Metadata m;
  EXPECT_TRUE(parse(std::string(64, 'k') + "=v\n", &m).ok());
  EXPECT_EQ(parse(std::string(65, 'k') + "=v\n", &m).status, Status::kBadMetadata);
}

TEST(Metadata, EntryCountLimit) {
  std::string text;
  for (int i = 0; i < 1025; ++i) text += "k" + std::to_string(i) + "=\n";
  Metadata m;
  EXPECT_EQ(parse(text, &m).status, Status::kBadMetadata);
}

}  // namespace
}  // namespace mrsv

namespace mrsv {
namespace {

// spec 2.6 number grammar, independent of the locale.
TEST(Metadata, NumberListGrammar) {
  for (const char* good : {"1", "-2.5", "+.5", "1.", "1e3", "6.02E+23,1,-0", "30,30"})
    EXPECT_TRUE(metadataEntryProblem("spacing", good).empty()) << good;
  for (const char* bad : {"", ".", "e5", "1e", "1,,2", "1,", "0x10", "inf", "nan", "1 2", "1.2.3"})
    EXPECT_FALSE(metadataEntryProblem("origin", bad).empty()) << bad;
}

}  // namespace
}  // namespace mrsv

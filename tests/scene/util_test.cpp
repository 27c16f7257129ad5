// The utility layer's spellings round-trip: what hash_hex writes, parse_hash_hex reads back, and
// nothing else; extensions compare lower-cased.
#include <kdray/util.h>

#include <gtest/gtest.h>

namespace kdray {
namespace {

TEST(Util, HashHexRoundTrips) {
  for (uint64_t hash : {uint64_t(0), uint64_t(0x0123456789abcdefull), ~uint64_t(0)}) {
    EXPECT_EQ(hash_hex(hash).size(), 16u);
    EXPECT_EQ(parse_hash_hex(hash_hex(hash)), hash);
  }
}

TEST(Util, ParseHashHexTakesOnlyWhatHashHexWrites) {
  for (const char* text : {"", "0", "0123456789ABCDEF", "0x23456789abcdef", "0123456789abcdef0", " 123456789abcdef"})
    EXPECT_FALSE(parse_hash_hex(text)) << '"' << text << '"';
}

TEST(Util, LowercaseExtension) {
  EXPECT_EQ(lowercase_extension("a/Model.EXR"), ".exr");
  EXPECT_EQ(lowercase_extension("noext"), "");
}

}  // namespace
}  // namespace kdray

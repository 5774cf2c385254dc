#include "mrsv/status.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace mrsv {
namespace {

TEST(Status, EveryCodeHasAUniqueName) {
  std::set<std::string> names;
  int named = 0;
  for (int code = 0; code < 1000; ++code) {
    std::string name = statusName(static_cast<Status>(code));
    if (name == "unknown_status") continue;
    ++named;
    EXPECT_TRUE(names.insert(name).second) << name;
  }
  EXPECT_EQ(named, 33);  // update with Annex A when a code is added (207, 208: spec 11)
}

TEST(Status, DescribeNamesOffsetCodeFieldAndRule) {
  Error e{Status::kChunkPastEnd, 40, "GRAW.chunk_length", "chunk needs 100 bytes"};
  EXPECT_EQ(e.describe(), "offset 40: E111 chunk_past_end: GRAW.chunk_length: chunk needs 100 bytes");
}

}  // namespace
}  // namespace mrsv

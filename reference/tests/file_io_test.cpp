#include "mrsv/file_io.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

namespace mrsv {
namespace {

std::string tempDir() {
  std::string pattern = testing::TempDir() + "mrsv-test-XXXXXX";
  const char* dir = mkdtemp(pattern.data());
  EXPECT_NE(dir, nullptr);
  return dir ? dir : "";
}

int countEntries(const std::string& dir) {
  int n = 0;
  DIR* d = opendir(dir.c_str());
  while (dirent* e = readdir(d)) n += e->d_name[0] != '.';
  closedir(d);
  return n;
}

TEST(FileIo, AtomicWriteReplacesWholeAndLeavesNoTemporary) {
  std::string dir = tempDir();
  std::string path = dir + "/out.bin";
  std::string error;
  ASSERT_TRUE(writeFileAtomically(path, {1, 2, 3}, &error)) << error;
  ASSERT_TRUE(writeFileAtomically(path, {4, 5}, &error)) << error;
  std::vector<uint8_t> back;
  ASSERT_TRUE(readWholeFile(path, &back, &error)) << error;
  EXPECT_EQ(back, (std::vector<uint8_t>{4, 5}));
  EXPECT_EQ(countEntries(dir), 1);
  unlink(path.c_str());
  rmdir(dir.c_str());
}

TEST(FileIo, FailedWriteLeavesNothing) {
  std::string dir = tempDir();
  std::string error;
  EXPECT_FALSE(writeFileAtomically(dir + "/missing/sub/out.bin", {1}, &error));
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(countEntries(dir), 0);
  rmdir(dir.c_str());
}

TEST(FileIo, SameFileThroughDifferentPaths) {
  std::string dir = tempDir();
  std::string path = dir + "/a.bin";
  std::string error;
  ASSERT_TRUE(writeFileAtomically(path, {1}, &error));
  EXPECT_TRUE(isSameFile(path, dir + "/./a.bin"));
  EXPECT_FALSE(isSameFile(path, dir + "/b.bin"));
  unlink(path.c_str());
  rmdir(dir.c_str());
}

TEST(FileIo, ReadingADirectoryIsAnError) {
  std::vector<uint8_t> out;
  std::string error;
  EXPECT_FALSE(readWholeFile("/", &out, &error));
  EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace mrsv

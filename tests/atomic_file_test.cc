// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Output files never replace what is not theirs (issue 9): devices and
// FIFOs are written through, links followed, directories refused, and no
// temporary is left behind.

#include "fit3dof/atomic_file.h"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "fit3dof/input_error.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> Names(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    names.push_back(e.path().filename().string());
  }
  return names;
}

TEST(AtomicFile, WritesNewAndRegularFiles) {
  const std::string dir = testing::ScratchDirectory("atomic_regular");
  WriteFileAtomically(dir + "/sub/a.txt", "one\n");
  WriteFileAtomically(dir + "/sub/a.txt", "two\n");
  EXPECT_EQ(testing::ReadText(dir + "/sub/a.txt"), "two\n");
  EXPECT_EQ(Names(dir + "/sub"), std::vector<std::string>{"a.txt"});
  struct stat st;
  ASSERT_EQ(::stat((dir + "/sub/a.txt").c_str(), &st), 0);
  EXPECT_NE(st.st_mode & S_IRGRP, 0u) << "mkstemp's 0600 was kept";
}

TEST(AtomicFile, DevNullStaysADevice) {
  WriteFileAtomically("/dev/null", "discarded\n");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(AtomicFile, FollowsSymbolicLinks) {
  const std::string dir = testing::ScratchDirectory("atomic_link");
  testing::WriteText(dir + "/target.txt", "old\n");
  fs::create_symlink("target.txt", dir + "/link.txt");
  WriteFileAtomically(dir + "/link.txt", "new\n");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir + "/link.txt")));
  EXPECT_EQ(testing::ReadText(dir + "/target.txt"), "new\n");
}

TEST(AtomicFile, WritesThroughAFifo) {
  const std::string dir = testing::ScratchDirectory("atomic_fifo");
  const std::string fifo = dir + "/pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = testing::ReadText(fifo); });
  WriteFileAtomically(fifo, "through the pipe\n");
  reader.join();
  EXPECT_EQ(received, "through the pipe\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(AtomicFile, RefusesDirectoriesAndLeavesNoTemporary) {
  const std::string dir = testing::ScratchDirectory("atomic_refuse");
  fs::create_directories(dir + "/out.csv");
  EXPECT_THROW(WriteFileAtomically(dir + "/out.csv", "x"), InputError);
  testing::WriteText(dir + "/file", "not a directory\n");
  EXPECT_THROW(WriteFileAtomically(dir + "/file/out.csv", "x"), InputError);
  std::vector<std::string> names = Names(dir);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"file", "out.csv"}));
}

TEST(AtomicFile, ThreadsWritingOnePathNeverShareATemporary) {
  const std::string dir = testing::ScratchDirectory("atomic_threads");
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&, t] {
      const std::string text(10000, static_cast<char>('a' + t));
      for (int i = 0; i < 20; ++i) WriteFileAtomically(dir + "/x.txt", text);
    });
  }
  for (std::thread& t : threads) t.join();
  const std::string final_text = testing::ReadText(dir + "/x.txt");
  ASSERT_EQ(final_text.size(), 10000u);
  EXPECT_EQ(final_text, std::string(10000, final_text[0]));
  EXPECT_EQ(Names(dir), std::vector<std::string>{"x.txt"});
}

TEST(AtomicFile, NamesItsTemporaries) {
  EXPECT_TRUE(IsTemporaryFileName("report.json.tmp.a1B2c3"));
  EXPECT_FALSE(IsTemporaryFileName("report.json"));
  EXPECT_FALSE(IsTemporaryFileName("run.tmp.json"));
}

}  // namespace
}  // namespace fit3dof

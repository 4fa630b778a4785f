// Atomic file writing: content lands whole or not at all, and no temporary stays.
#include "output/atomic_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/base/error.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::error_of;
using test::read_file;
using test::TempDir;

bool exists(const std::string& path) { return std::filesystem::exists(path); }

namespace fs = std::filesystem;

// The folder (and its subfolders) holds no temporary of ilp's, named "....tmp-..."
// (a file) or ".NAME.ilp-..." (a staging folder).
::testing::AssertionResult no_temporaries(const TempDir& dir) {
  for (const auto& entry : fs::recursive_directory_iterator(dir.file(""))) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos || name.find(".ilp-") != std::string::npos)
      return ::testing::AssertionFailure() << "temporary left: " << entry.path();
  }
  return ::testing::AssertionSuccess();
}

std::vector<std::string> names_in(const std::string& folder) {
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(folder)) out.push_back(entry.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(AtomicFile, ContentLandsAndNoTemporaryRemains) {
  TempDir dir;
  const std::string path = dir.write("out.txt", "old content that is longer\n");
  write_file_atomically(path, [](std::ostream& out) { out << "line 1\nline 2\n"; });
  EXPECT_EQ(read_file(path), "line 1\nline 2\n");
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(AtomicFile, ThrowingWriterLeavesThePreviousFileAndNoTemporary) {
  TempDir dir;
  const std::string path = dir.write("out.txt", "previous\n");
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& out) {
                                       out << "half of it";
                                       throw std::runtime_error("writer failed");
                                     }),
               std::runtime_error);
  EXPECT_EQ(read_file(path), "previous\n");
  EXPECT_TRUE(no_temporaries(dir));

  const std::string fresh = dir.file("fresh.txt");
  EXPECT_THROW(write_file_atomically(fresh, [](std::ostream&) { throw std::runtime_error("writer failed"); }),
               std::runtime_error);
  EXPECT_FALSE(exists(fresh));
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(AtomicFile, FailedStreamIsAnErrorNamingThePath) {
  TempDir dir;
  const std::string path = dir.write("out.txt", "previous\n");
  const std::string message = error_of<IlpError>([&] {
    write_file_atomically(path, [](std::ostream& out) {
      out << "some";
      out.setstate(std::ios::badbit);  // as a full disk would
    });
  });
  EXPECT_EQ(message, path + ": write failed");
  EXPECT_EQ(read_file(path), "previous\n");
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(AtomicFile, UnwritablePathIsAnErrorNamingThePath) {
  TempDir dir;
  const std::string path = dir.file("no_such_folder/out.txt");
  bool called = false;
  const std::string message =
      error_of<IlpError>([&] { write_file_atomically(path, [&](std::ostream&) { called = true; }); });
  EXPECT_EQ(message, path + ": cannot write");
  EXPECT_FALSE(called);
  EXPECT_FALSE(exists(path));
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(AtomicFile, FolderInTheWayIsAnErrorNamingThePath) {
  TempDir dir;
  const std::string path = dir.file("folder");
  std::filesystem::create_directories(path + "/inside");
  const std::string message =
      error_of<IlpError>([&] { write_file_atomically(path, [](std::ostream& out) { out << "text"; }); });
  EXPECT_TRUE(test::StartsWith(message, path + ": write failed"));
  EXPECT_TRUE(std::filesystem::is_directory(path + "/inside"));
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(AtomicFile, TemporariesOfGoneProcessesAreRemovedOthersKept) {
  TempDir dir;
  const std::string path = dir.file("out.txt");
  dir.write("out.txt.tmp-999999999-3", "a killed run's");  // no such process
  dir.write("out.txt.tmp-1-3", "init's: still running");
  write_file_atomically(path, [](std::ostream& out) { out << "new\n"; });
  EXPECT_EQ(names_in(dir.file("")), (std::vector<std::string>{"out.txt", "out.txt.tmp-1-3"}));
}

// ---------------------------------------------------------------------------------
// OutputSet: the files of one command, replaced as one transaction

TEST(OutputSet, FreshFolderGetsTheSet) {
  TempDir dir;
  const std::string folder = dir.file("results/job");
  OutputSet set(folder, {"a.txt", "b.txt"});
  set.write("a.txt", [](std::ostream& out) { out << "A\n"; });
  set.write("b.txt", [](std::ostream& out) { out << "B\n"; });
  EXPECT_FALSE(exists(folder));  // nothing in place before the commit
  EXPECT_EQ(set.commit(), (std::vector<std::string>{folder + "/a.txt", folder + "/b.txt"}));
  EXPECT_EQ(read_file(folder + "/a.txt"), "A\n");
  EXPECT_EQ(read_file(folder + "/b.txt"), "B\n");
  EXPECT_EQ(names_in(dir.file("results")), (std::vector<std::string>{"job"}));
}

// Writers running at once (ilp run writes its pictures in parallel): each file listed
// once, a batch's files in the owned order whatever order they finish in, after the
// files staged before it.
TEST(OutputSet, ABatchOfWritersAtOnceListsItsFilesInTheOwnedOrder) {
  TempDir dir;
  const std::string folder = dir.file("out");
  std::vector<std::string> owned;
  for (int k = 0; k < 24; ++k) owned.push_back("f" + std::to_string(k) + ".txt");
  OutputSet set(folder, owned);
  set.write("f23.txt", [](std::ostream& out) { out << "first\n"; });
  set.begin_batch();
  std::vector<std::thread> writers;
  for (int k = 22; k >= 0; --k)
    writers.emplace_back([&set, k] { set.write("f" + std::to_string(k) + ".txt", [k](std::ostream& out) { out << k << "\n"; }); });
  for (std::thread& t : writers) t.join();
  set.end_batch();
  std::vector<std::string> expected{folder + "/f23.txt"};
  for (int k = 0; k < 23; ++k) expected.push_back(folder + "/f" + std::to_string(k) + ".txt");
  EXPECT_EQ(set.commit(), expected);
  EXPECT_EQ(read_file(folder + "/f7.txt"), "7\n");
}

// A building's set: its own files and a sub-folder per room. The rooms folder is owned
// as a whole, so a room of the previous run that this run does not write is gone.
TEST(OutputSet, SubfoldersAreStagedAndCommittedWithTheSet) {
  TempDir dir;
  const std::string folder = dir.file("out");
  fs::create_directories(folder + "/rooms/old_room");
  dir.write("out/rooms/old_room/result.json", "old\n");
  dir.write("out/notes.txt", "the user's\n");
  OutputSet set(folder, {"result.json", "rooms", "rooms/a/result.json", "rooms/b/result.json"});
  set.set_subfolder("rooms/a");
  set.write("result.json", [](std::ostream& out) { out << "A\n"; });
  EXPECT_THROW((void)set.staging_path("plan.svg"), std::invalid_argument);  // rooms/a/plan.svg is not owned
  set.set_subfolder("");
  set.write("result.json", [](std::ostream& out) { out << "building\n"; });
  EXPECT_EQ(read_file(folder + "/rooms/old_room/result.json"), "old\n");  // nothing in place before the commit
  EXPECT_EQ(set.commit(), (std::vector<std::string>{folder + "/rooms/a/result.json", folder + "/result.json"}));
  EXPECT_EQ(read_file(folder + "/rooms/a/result.json"), "A\n");
  EXPECT_EQ(read_file(folder + "/result.json"), "building\n");
  EXPECT_EQ(read_file(folder + "/notes.txt"), "the user's\n");
  EXPECT_EQ(names_in(folder + "/rooms"), (std::vector<std::string>{"a"}));
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(OutputSet, ReplacesItsOwnFilesKeepsOthersAndDropsOwnedFilesNotWritten) {
  TempDir dir;
  const std::string folder = dir.file("out");
  fs::create_directories(folder + "/sub");
  dir.write("out/a.txt", "old A\n");
  dir.write("out/b.txt", "old B: a format this run leaves out\n");
  dir.write("out/sweep.csv", "another command's\n");
  dir.write("out/sub/notes.txt", "the user's\n");
  OutputSet set(folder, {"a.txt", "b.txt"});
  set.write("a.txt", [](std::ostream& out) { out << "new A\n"; });
  set.commit();
  EXPECT_EQ(names_in(folder), (std::vector<std::string>{"a.txt", "sub", "sweep.csv"}));
  EXPECT_EQ(read_file(folder + "/a.txt"), "new A\n");
  EXPECT_EQ(read_file(folder + "/sweep.csv"), "another command's\n");
  EXPECT_EQ(read_file(folder + "/sub/notes.txt"), "the user's\n");
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(OutputSet, FailureBeforeTheCommitLeavesThePreviousSetWhole) {
  TempDir dir;
  const std::string folder = dir.file("out");
  fs::create_directories(folder);
  dir.write("out/a.txt", "old A\n");
  dir.write("out/b.txt", "old B\n");
  {
    OutputSet set(folder, {"a.txt", "b.txt"});
    set.write("a.txt", [](std::ostream& out) { out << "new A\n"; });
    EXPECT_THROW(set.write("b.txt", [](std::ostream&) { throw IlpError("disk full"); }), IlpError);
  }  // no commit
  EXPECT_EQ(read_file(folder + "/a.txt"), "old A\n");
  EXPECT_EQ(read_file(folder + "/b.txt"), "old B\n");
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(OutputSet, StagingFoldersOfGoneProcessesAreRemovedAtTheCommit) {
  TempDir dir;
  const std::string folder = dir.file("out");
  fs::create_directories(dir.file(".out.ilp-tmp-999999999-0badf00d/inside"));
  fs::create_directories(dir.file(".out.ilp-tmp-1-0badf00d"));  // init's: left alone
  OutputSet set(folder, {"a.txt"});
  set.write("a.txt", [](std::ostream& out) { out << "A\n"; });
  set.commit();
  EXPECT_EQ(names_in(dir.file("")), (std::vector<std::string>{".out.ilp-tmp-1-0badf00d", "out"}));
}

// A commit killed between the two renames of the fallback (no RENAME_EXCHANGE) left
// the previous set aside and no folder: the next commit puts it back first, so the
// files it does not own survive.
TEST(OutputSet, FolderLeftAsideByAKilledCommitIsPutBack) {
  TempDir dir;
  const std::string folder = dir.file("out");
  fs::create_directories(dir.file(".out.ilp-old-999999999-0badf00d"));
  dir.write(".out.ilp-old-999999999-0badf00d/notes.txt", "the user's\n");
  dir.write(".out.ilp-old-999999999-0badf00d/a.txt", "old A\n");
  OutputSet set(folder, {"a.txt"});
  set.write("a.txt", [](std::ostream& out) { out << "new A\n"; });
  set.commit();
  EXPECT_EQ(names_in(folder), (std::vector<std::string>{"a.txt", "notes.txt"}));
  EXPECT_EQ(read_file(folder + "/a.txt"), "new A\n");
  EXPECT_EQ(read_file(folder + "/notes.txt"), "the user's\n");
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(OutputSet, FileWhereTheFolderShouldBeIsRefusedUpFront) {
  TempDir dir;
  const std::string folder = dir.write("out", "a file\n");
  const std::string message = error_of<IlpError>([&] { OutputSet set(folder, {"a.txt"}); });
  EXPECT_EQ(message, folder + ": is not a folder (the output folder)");
  EXPECT_EQ(read_file(folder), "a file\n");
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(OutputSet, CurrentFolderOrAnAncestorCannotBeTheOutputFolder) {
  for (const char* folder : {".", "./", "..", "/"}) {
    const std::string message = error_of<IlpError>([&] { OutputSet set(folder, {"a.txt"}); });
    EXPECT_TRUE(test::StartsWith(message, std::string(folder) + ": ")) << message;
  }
}

}  // namespace
}  // namespace ilp

// Atomic file writing: content lands whole or not at all, and no temporary stays.
#include "output/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "core/error.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::error_of;
using test::read_file;
using test::TempDir;

bool exists(const std::string& path) { return std::filesystem::exists(path); }

TEST(AtomicFile, ContentLandsAndNoTemporaryRemains) {
  TempDir dir;
  const std::string path = dir.write("out.txt", "old content that is longer\n");
  write_file_atomically(path, [](std::ostream& out) { out << "line 1\nline 2\n"; });
  EXPECT_EQ(read_file(path), "line 1\nline 2\n");
  EXPECT_FALSE(exists(path + ".tmp"));
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
  EXPECT_FALSE(exists(path + ".tmp"));

  const std::string fresh = dir.file("fresh.txt");
  EXPECT_THROW(write_file_atomically(fresh, [](std::ostream&) { throw std::runtime_error("writer failed"); }),
               std::runtime_error);
  EXPECT_FALSE(exists(fresh));
  EXPECT_FALSE(exists(fresh + ".tmp"));
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
  EXPECT_FALSE(exists(path + ".tmp"));
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
  EXPECT_FALSE(exists(path + ".tmp"));
}

TEST(AtomicFile, FolderInTheWayIsAnErrorNamingThePath) {
  TempDir dir;
  const std::string path = dir.file("folder");
  std::filesystem::create_directories(path + "/inside");
  const std::string message =
      error_of<IlpError>([&] { write_file_atomically(path, [](std::ostream& out) { out << "text"; }); });
  EXPECT_TRUE(test::StartsWith(message, path + ": write failed"));
  EXPECT_TRUE(std::filesystem::is_directory(path + "/inside"));
  EXPECT_FALSE(exists(path + ".tmp"));
}

}  // namespace
}  // namespace ilp

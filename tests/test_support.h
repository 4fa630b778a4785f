// Helpers shared by the test programs (header only): a temporary folder per test,
// reading a file whole, checks of error messages, and catching the one exception a
// call must throw.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <typeinfo>
#include <vector>

namespace ilp::test {

// Built with AddressSanitizer (scripts/sanitize.sh): its own handlers turn a crash or an
// exhausted allocator into a report and exit status 1, where a plain build dies by the
// signal or throws std::bad_alloc; the death tests that watch those say which they expect.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

// A fresh folder under the system temp dir, named after the process and the running
// test (so unique per test, also with ctest -j), removed when the test ends.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("ilp_test_") + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" +
                       info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  // Writes `content` byte for byte (no newline translation) and returns the full path.
  std::string write(const std::string& name, const std::string& content) const {
    const std::filesystem::path p = path_ / name;
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p.string();
  }
  // Full path of `name` in the folder; the file need not exist.
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// The whole file, byte for byte; "" when it cannot be read.
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// For EXPECT_TRUE: `text` contains `part`. `what` names the text in the failure.
inline ::testing::AssertionResult Contains(const std::string& text, const std::string& part,
                                           const char* what = "message") {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << "\n  \"" << text << "\"\ndoes not contain\n  \"" << part << "\"";
}

// For EXPECT_TRUE: `text` starts with `prefix`.
inline ::testing::AssertionResult StartsWith(const std::string& text, const std::string& prefix) {
  if (text.rfind(prefix, 0) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "message\n  \"" << text << "\"\ndoes not start with\n  \"" << prefix << "\"";
}

// `message` starts with `start` and contains each of `parts`; each miss is its own
// failure.
inline void expect_message(const std::string& message, const std::string& start,
                           const std::vector<std::string>& parts) {
  EXPECT_TRUE(StartsWith(message, start));
  for (const std::string& part : parts) EXPECT_TRUE(Contains(message, part));
}

// Runs f, which must throw exactly an E (not another ilp error); returns what().
// Another exception, or none, is a test failure (`call`, if given, names what was
// run) and gives "".
template <class E, class F>
std::string error_of(F&& f, const std::string& call = "") {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw the wrong exception type (" << typeid(e).name() << "): " << e.what();
    return {};
  }
  ADD_FAILURE() << (call.empty() ? "" : call + " ") << "did not throw";
  return {};
}

}  // namespace ilp::test

// SVG to PNG: a valid PNG of the document's size times the scale, written atomically;
// unreadable documents and bad scales fail with the file's name and leave nothing.
#include "output/png_render.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/base/error.h"
#include "tests/output/png_checks.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::error_of;
using test::TempDir;

const std::string kSvg =
    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"120\" height=\"80\" viewBox=\"0 0 120 80\">"
    "<rect x=\"10\" y=\"10\" width=\"50\" height=\"30\" fill=\"#336699\"/>"
    "<text x=\"20\" y=\"70\" font-family=\"sans-serif\" font-size=\"12\">500 lx</text></svg>";

TEST(PngRender, WritesAValidPngOfTheScaledSize) {
  TempDir dir;
  const std::string path = dir.file("plan.png");
  write_png_from_svg(path, kSvg, 1.0);
  EXPECT_EQ(test::png_size(test::read_file(path)), std::make_pair(120L, 80L));
  write_png_from_svg(path, kSvg, 2.5);  // replaces the previous file
  EXPECT_EQ(test::png_size(test::read_file(path)), std::make_pair(300L, 200L));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(PngRender, UnreadableSvgFailsNamingTheFileAndWritesNothing) {
  TempDir dir;
  const std::string path = dir.file("plan.png");
  test::expect_message(error_of<IlpError>([&] { write_png_from_svg(path, "<svg><rect></svg>", 1.0); }), path + ": ",
                       {"SVG"});
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  // No size: nothing to render.
  const std::string sizeless = "<svg xmlns=\"http://www.w3.org/2000/svg\"><rect width=\"5\" height=\"5\"/></svg>";
  EXPECT_TRUE(test::StartsWith(error_of<IlpError>([&] { write_png_from_svg(path, sizeless, 1.0); }), path + ": "));
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(PngRender, ScaleAndSizeAreChecked) {
  TempDir dir;
  const std::string path = dir.file("plan.png");
  EXPECT_TRUE(test::Contains(error_of<IlpError>([&] { write_png_from_svg(path, kSvg, 0.0); }), "scale"));
  EXPECT_TRUE(test::Contains(error_of<IlpError>([&] { write_png_from_svg(path, kSvg, 200.0); }), "scale"));
  const std::string huge = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20000\" height=\"10\"></svg>";
  EXPECT_TRUE(test::Contains(error_of<IlpError>([&] { write_png_from_svg(path, huge, 1.0); }), "out of range"));
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(PngRender, UnwritableFolderFailsNamingTheFile) {
  const std::string path = "/nonexistent-folder-ilp/plan.png";
  EXPECT_TRUE(test::StartsWith(error_of<IlpError>([&] { write_png_from_svg(path, kSvg, 1.0); }), path + ": "));
}

}  // namespace
}  // namespace ilp

// StaticFiles (static_files.hpp): the page's files are found, and nothing outside the mounted
// directories can be named, however the request spells it (.., encoded .., backslashes, NUL,
// absolute paths, a symlink leading out).
#include "realtime/static_files.hpp"

#include "core/base/error.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

namespace fs = std::filesystem;
using tmlab::rt::StaticFiles;
using tmlab::testing::write_file;

class StaticFilesTest : public tmlab::testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    fs::create_directories(dir_ / "page" / "sub");
    fs::create_directories(dir_ / "vendor");
    write_file(dir_ / "page" / "index.html", "<html>");
    write_file(dir_ / "page" / "app.js", "js");
    write_file(dir_ / "page" / "sub" / "index.html", "sub");
    write_file(dir_ / "vendor" / "three.module.js", "three");
    write_file(dir_ / "secret.txt", "secret");  // beside the mounts: must never be served
    files_.mount("/", dir_ / "page");
    files_.mount("/vendor/three/", dir_ / "vendor");
  }
  std::string resolved(const std::string& target) const {
    const auto p = files_.resolve(target);
    return p ? p->filename().string() : std::string("<none>");
  }
  StaticFiles files_;
};

TEST_F(StaticFilesTest, FindsThePageAndTheVendorFiles) {
  EXPECT_EQ(resolved("/"), "index.html");
  EXPECT_EQ(resolved("/index.html"), "index.html");
  EXPECT_EQ(resolved("/app.js?v=3#x"), "app.js");
  EXPECT_EQ(resolved("/sub/"), "index.html");
  EXPECT_EQ(*files_.resolve("/sub/"), fs::canonical(dir_ / "page" / "sub" / "index.html"));
  EXPECT_EQ(resolved("/vendor/three/three.module.js"), "three.module.js");
  EXPECT_EQ(resolved("/%61pp.js"), "app.js");  // percent-decoding of an allowed character
  EXPECT_EQ(resolved("/missing.js"), "<none>");
  EXPECT_EQ(resolved("/sub"), "<none>");  // a directory, not a file
  // A mount's files come from its own directory only: no fall-back to the page's.
  EXPECT_EQ(resolved("/vendor/three/index.html"), "<none>");
}

TEST_F(StaticFilesTest, RefusesEveryPathOutOfTheMounts) {
  for (const char* t : {"/../secret.txt",
                        "/sub/../../secret.txt",
                        "/%2e%2e/secret.txt",
                        "/%2E%2E/secret.txt",
                        "/..%2fsecret.txt",
                        "/.%2e/secret.txt",
                        "/vendor/three/../../secret.txt",
                        "/vendor/three/%2e%2e/%2e%2e/secret.txt",
                        "/..\\secret.txt",
                        "/%5c..%5csecret.txt",
                        "//etc/passwd",
                        "/./index.html",
                        "/sub//index.html",
                        "/index.html%00.js",
                        "/%",
                        "/%zz",
                        "/%252e%252e/secret.txt",
                        "index.html",
                        "",
                        "/ index.html",
                        "/~/secret.txt",
                        "/%c0%ae%c0%ae/secret.txt"})
    EXPECT_EQ(resolved(t), "<none>") << "'" << t << "'";
}

TEST_F(StaticFilesTest, RefusesASymlinkLeadingOut) {
  std::error_code ec;
  fs::create_symlink(dir_ / "secret.txt", dir_ / "page" / "link.txt", ec);
  if (ec) GTEST_SKIP() << "cannot create a symlink here: " << ec.message();
  EXPECT_EQ(resolved("/link.txt"), "<none>");
}

TEST(StaticFiles, ContentTypesAndBadMounts) {
  EXPECT_EQ(StaticFiles::content_type("a/b.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(StaticFiles::content_type("index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(StaticFiles::content_type("x.bin"), "application/octet-stream");
  StaticFiles f;
  EXPECT_THROW(f.mount("vendor/", "/tmp"), tmlab::Error);
  EXPECT_THROW(f.mount("/vendor", "/tmp"), tmlab::Error);
  f.mount("/", "/nonexistent-tmlab-dir");
  EXPECT_FALSE(f.resolve("/index.html"));  // a missing directory serves nothing, it does not throw
}

}  // namespace

// `tmlab realtime CASE --serve` as a user meets it (issue 17, docs/realtime.md "The live page").
//   ServeCli.*     (always run): --port 0 prints the URL, the page is served and nothing outside it
//                  (path traversal over a raw socket), a taken port is a clear error, bad --port
//                  values are refused, SIGINT stops the run cleanly (exit 0, the timing printed).
//   ServeBrowser.* (ctest label `browser`): Debian's Chromium, driven by playwright-core
//                  (realtime/web/tests/browser_test.mjs): the page loads, frames arrive, a mouse drag
//                  of the probe changes the reported force, the wheel during a drag presses the
//                  probe in along the view direction (the force grows) and Shift+wheel pulls it out;
//                  the screenshots are kept in <build>/test-artifacts/realtime_serve.png and
//                  realtime_serve_depth.png. Skipped, with the reason, when
//                  Chromium, node or playwright-core (./tmlab set-up) is absent.
// No timing assertion: the waits only bound how long a broken server can hang the test.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;
using tmlab::cli_test::Result;
using tmlab::testing::read_file;

/// Waits (up to 5 minutes) until the server's log names its port; 0 when it never does.
int wait_for_port(const fs::path& log) {
  const std::regex url(R"(serving http://127\.0\.0\.1:([0-9]+)/)");
  for (int i = 0; i < 3000; ++i) {
    std::smatch m;
    const std::string text = read_file(log);
    if (std::regex_search(text, m, url)) return std::stoi(m[1]);
    if (text.find("error") != std::string::npos) return 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

/// Sends `request` verbatim to 127.0.0.1:port and returns the whole reply.
std::string raw_http(int port, const std::string& request) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string reply;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      ::send(fd, request.data(), request.size(), 0) == static_cast<ssize_t>(request.size())) {
    char buf[4096];
    for (ssize_t n; (n = ::recv(fd, buf, sizeof buf, 0)) > 0;) reply.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return reply;
}

std::string get(int port, const std::string& target) {
  return raw_http(port, "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                            "\r\nConnection: close\r\n\r\n");
}

class ServeCli : public tmlab::cli_test::CliTest {};

TEST_F(ServeCli, ServesThePageRefusesTraversalAndStopsOnSigint) {
  const fs::path log = dir_ / "serve.txt";
  const pid_t pid = tmlab::cli_test::spawn({"realtime", "liver-poke", "--serve", "--port", "0"}, log);
  const int port = wait_for_port(log);
  if (port == 0) {
    ::kill(pid, SIGKILL);
    tmlab::cli_test::wait_exit(pid);
    FAIL() << read_file(log);
  }
  const std::string page = get(port, "/");
  EXPECT_EQ(page.rfind("HTTP/1.1 200", 0), 0u) << page;
  EXPECT_NE(page.find("app.js"), std::string::npos);
  EXPECT_EQ(get(port, "/app.js").rfind("HTTP/1.1 200", 0), 0u);
  for (const char* t : {"/../CMakeLists.txt", "/%2e%2e/CMakeLists.txt", "/..%2f..%2fCMakeLists.txt",
                        "/vendor/three/../../../../CMakeLists.txt", "/../../../../../etc/passwd"}) {
    const std::string r = get(port, t);
    EXPECT_EQ(r.rfind("HTTP/1.1 404", 0), 0u) << t << ": " << r;
    EXPECT_EQ(r.find("cmake_minimum_required"), std::string::npos) << t;
  }
  // A second server on the same port: a clear error, exit status 1.
  const Result taken = tmlab({"realtime", "liver-poke", "--serve", "--port", std::to_string(port)});
  EXPECT_EQ(taken.status, 1) << taken.output;
  EXPECT_NE(taken.output.find("port " + std::to_string(port) + " on 127.0.0.1 is already in use"),
            std::string::npos)
      << taken.output;
  // SIGINT: the run stops, closes the server and prints its timing; exit status 0.
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  EXPECT_EQ(tmlab::cli_test::wait_exit(pid), 0) << read_file(log);
  const std::string out = read_file(log);
  EXPECT_NE(out.find("stopped (SIGINT)"), std::string::npos) << out;
  EXPECT_NE(out.find("haptic   target  1000.0 Hz"), std::string::npos) << out;
  EXPECT_NE(out.find("refused: no file for '/../CMakeLists.txt'"), std::string::npos) << out;
}

TEST_F(ServeCli, BadOptionsAreRefused) {
  // One number grammar (core/base/number.hpp): no hex, no blanks, no exponent for a whole number.
  for (const char* port : {"-1", "65536", "1.5", "http", "0x4A3B", " 1.9e4", "1.9e4", "8765 "}) {
    const Result r = tmlab({"realtime", "liver-poke", "--serve", "--port", port});
    EXPECT_EQ(r.status, 2) << port << ": " << r.output;
    EXPECT_NE(r.output.find("--port"), std::string::npos) << r.output;
  }
  Result r = tmlab({"realtime", "liver-poke", "--port", "8765"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--port goes with --serve"), std::string::npos) << r.output;
  r = tmlab({"realtime", "liver-poke", "--serve", "--record"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("exclude each other"), std::string::npos) << r.output;
  r = tmlab({"realtime", "liver-poke", "--serve", "--results", dir_.string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--results only applies with --record"), std::string::npos) << r.output;
}

// ---------------------------------------------------------------- the browser test

/// The first executable of `names` found on PATH (or given by absolute path); "" when none is.
std::string find_program(const std::vector<std::string>& names) {
  const char* path = std::getenv("PATH");
  for (const std::string& n : names) {
    if (n.front() == '/') {
      if (::access(n.c_str(), X_OK) == 0) return n;
      continue;
    }
    std::string dirs = path ? path : "/usr/bin:/bin";
    for (std::size_t b = 0; b <= dirs.size();) {
      const std::size_t e = std::min(dirs.find(':', b), dirs.size());
      const fs::path p = fs::path(dirs.substr(b, e - b)) / n;
      if (::access(p.c_str(), X_OK) == 0) return p.string();
      b = e + 1;
    }
  }
  return "";
}

class ServeBrowser : public tmlab::cli_test::CliTest {};

TEST_F(ServeBrowser, PageShowsFramesAndADragChangesTheForce) {
  const char* env = std::getenv("TMLAB_CHROMIUM");
  const std::string chromium = find_program(env ? std::vector<std::string>{env}
                                                : std::vector<std::string>{"chromium", "chromium-browser"});
  if (chromium.empty())
    GTEST_SKIP() << "Chromium is not installed (Debian: apt-get install chromium; or set TMLAB_CHROMIUM): "
                    "the browser test of --serve is skipped";
  const std::string node = find_program({"node", "nodejs"});
  if (node.empty()) GTEST_SKIP() << "node is not installed (Debian: apt-get install nodejs npm): skipped";
  const fs::path npm_dir = fs::path(TMLAB_SOURCE_DIR) / "build" / "npm";
  if (!fs::exists(npm_dir / "node_modules" / "playwright-core" / "index.mjs"))
    GTEST_SKIP() << "playwright-core is not installed in " << npm_dir.string()
                 << " (./tmlab build installs it with npm): skipped";
  if (!fs::exists(npm_dir / "node_modules" / "three" / "build" / "three.module.js"))
    GTEST_SKIP() << "three.js is not installed in " << npm_dir.string()
                 << " (./tmlab build installs it): skipped";

  const fs::path log = dir_ / "serve.txt";
  const pid_t pid = tmlab::cli_test::spawn({"realtime", "liver-poke", "--serve", "--port", "0"}, log);
  const int port = wait_for_port(log);
  if (port == 0) {
    ::kill(pid, SIGKILL);
    tmlab::cli_test::wait_exit(pid);
    FAIL() << read_file(log);
  }
  const fs::path artifacts = fs::path(TMLAB_ARTIFACT_DIR);
  fs::create_directories(artifacts);
  const fs::path shot = artifacts / "realtime_serve.png", depth_shot = artifacts / "realtime_serve_depth.png";
  fs::remove(shot);
  fs::remove(depth_shot);
  const fs::path node_log = dir_ / "browser.txt";
  const tmlab::ProcessStatus st = tmlab::run_process(
      {node, (fs::path(TMLAB_SOURCE_DIR) / "realtime" / "web" / "tests" / "browser_test.mjs").string(),
       "http://127.0.0.1:" + std::to_string(port) + "/", shot.string(), npm_dir.string(), chromium},
      tmlab::ProcessOutput::to_file(node_log));
  ::kill(pid, SIGINT);
  const int exit_code = tmlab::cli_test::wait_exit(pid);
  const std::string browser = read_file(node_log);
  std::cout << "browser: " << browser;  // the measurements (frames/s received, forces), kept in the test log
  ASSERT_TRUE(st.ok()) << st.describe() << "\n" << browser << "\nserver:\n" << read_file(log);
  EXPECT_NE(browser.find("\"ok\":true"), std::string::npos) << browser;
  EXPECT_TRUE(fs::exists(shot) && fs::file_size(shot) > 1000) << shot;
  EXPECT_TRUE(fs::exists(depth_shot) && fs::file_size(depth_shot) > 1000) << depth_shot;
  EXPECT_NE(browser.find("\"along_view_m\""), std::string::npos) << browser;
  EXPECT_EQ(exit_code, 0) << read_file(log);
  const std::string out = read_file(log);
  std::cout << "server: " << out;  // its timing and page statistics
  EXPECT_NE(out.find("page connected"), std::string::npos) << out;
  EXPECT_EQ(out.find(" 0 probe moves"), std::string::npos) << out;
}

}  // namespace

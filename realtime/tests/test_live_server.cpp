// The live server (live_server.hpp) over real sockets, with Boost.Beast clients and no browser:
// the page's files and nothing else over HTTP, a clear error for a taken port, WebSocket frames out
// and probe targets in, foreign origins refused, and the whole chain on the liver: a probe moved
// through the WebSocket changes the force the frames report. No timing assertion (busy machine):
// the waits only bound how long a broken server can hang the test.
#include "realtime/live_server.hpp"

#include "core/base/error.hpp"
#include "core/testing/temp_dir.hpp"
#include "realtime/realtime_case.hpp"

#include <gtest/gtest.h>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

namespace {

namespace fs = std::filesystem;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using namespace tmlab;
using namespace tmlab::rt;
using Clock = std::chrono::steady_clock;

struct Reply {
  int status = 0;
  std::string body;
};

/// One HTTP request with the target sent verbatim (no client-side normalisation).
Reply http_request(int port, const std::string& target, http::verb verb = http::verb::get,
                   const std::string& host = "") {
  net::io_context ioc;
  tcp::socket s(ioc);
  s.connect(tcp::endpoint(net::ip::make_address_v4("127.0.0.1"), static_cast<unsigned short>(port)));
  http::request<http::string_body> req{verb, target, 11};
  req.set(http::field::host, host.empty() ? "127.0.0.1:" + std::to_string(port) : host);
  req.keep_alive(false);
  http::write(s, req);
  beast::flat_buffer b;
  http::response_parser<http::string_body> parser;
  parser.skip(verb == http::verb::head);  // a HEAD reply announces a body it does not send
  http::read(s, b, parser);
  return {static_cast<int>(parser.get().result_int()), parser.get().body()};
}

/// A WebSocket client of the server (what the page does, in C++).
class Page {
 public:
  explicit Page(int port, const std::string& origin = "") : ws_(ioc_) {
    ws_.next_layer().connect(
        tcp::endpoint(net::ip::make_address_v4("127.0.0.1"), static_cast<unsigned short>(port)));
    const std::string o = origin.empty() ? "http://127.0.0.1:" + std::to_string(port) : origin;
    ws_.set_option(websocket::stream_base::decorator(
        [o](websocket::request_type& req) { req.set(http::field::origin, o); }));
    ws_.handshake("127.0.0.1:" + std::to_string(port), "/ws");
  }
  /// The next message: text in `text`, or a decoded frame.
  bool next(std::string& text, LiveFrame& frame) {
    beast::flat_buffer b;
    ws_.read(b);
    const auto* p = static_cast<const std::uint8_t*>(b.data().data());
    if (ws_.got_text()) {
      text.assign(reinterpret_cast<const char*>(p), b.size());
      return true;
    }
    frame = decode_frame(p, b.size());
    return false;
  }
  LiveFrame next_frame() {
    std::string t;
    LiveFrame f;
    while (next(t, f)) {
    }
    return f;
  }
  void move_probe(const Vec3& x) {
    ws_.text(true);
    char msg[160];
    std::snprintf(msg, sizeof msg, R"({"type":"probe","x":[%.17g,%.17g,%.17g]})", x.x(), x.y(), x.z());
    ws_.write(net::buffer(std::string(msg)));
  }
  void send_text(const std::string& m) {
    ws_.text(true);
    ws_.write(net::buffer(m));
  }

 private:
  net::io_context ioc_;
  websocket::stream<tcp::socket> ws_;
};

class LiveServerTest : public tmlab::testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    fs::create_directories(dir_ / "page");
    tmlab::testing::write_file(dir_ / "page" / "index.html", "<html>live</html>");
    tmlab::testing::write_file(dir_ / "secret.txt", "secret");
  }
  LiveServerOptions options(int nodes = 2) const {
    LiveServerOptions o;
    o.port = 0;
    o.files.mount("/", dir_ / "page");
    o.hello = R"({"type":"hello"})";
    o.probe_box = {Vec3(-1, -1, -1), Vec3(1, 1, 1)};
    o.nodes = nodes;
    return o;
  }
};

TEST_F(LiveServerTest, ServesThePageAndNothingElse) {
  SeqLock<ProbeSample> probe;
  LiveServer server(options(), probe);
  ASSERT_GT(server.port(), 0);
  const int port = server.port();
  Reply r = http_request(port, "/");
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.body, "<html>live</html>");
  EXPECT_EQ(http_request(port, "/index.html", http::verb::head).status, 200);
  for (const char* t : {"/../secret.txt", "/%2e%2e/secret.txt", "/..%2fsecret.txt", "/page/../../secret.txt",
                        "//secret.txt", "/..\\secret.txt", "/nothing.js"})
    EXPECT_EQ(http_request(port, t).status, 404) << t;
  EXPECT_EQ(http_request(port, "/", http::verb::post).status, 405);
  // DNS rebinding: a page of another host name that resolves to 127.0.0.1 is refused.
  EXPECT_EQ(http_request(port, "/", http::verb::get, "evil.example:" + std::to_string(port)).status, 403);
  EXPECT_EQ(http_request(port, "/", http::verb::get, "localhost:" + std::to_string(port)).status, 200);
  EXPECT_GE(server.stats().refused, 8);
}

TEST_F(LiveServerTest, TakenPortIsAClearError) {
  SeqLock<ProbeSample> probe;
  LiveServer first(options(), probe);
  LiveServerOptions o = options();
  o.port = first.port();
  try {
    LiveServer second(std::move(o), probe);
    FAIL() << "a second server on port " << first.port() << " started";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("port " + std::to_string(first.port()) +
                                         " on 127.0.0.1 is already in use"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("--port 0"), std::string::npos) << e.what();
  }
  o = options();
  o.port = 70000;
  EXPECT_THROW(LiveServer(std::move(o), probe), Error);
}

TEST_F(LiveServerTest, WebSocketSendsFramesAndTakesProbeTargets) {
  SeqLock<ProbeSample> probe;
  LiveServer server(options(2), probe);
  Page page(server.port());
  std::string text;
  LiveFrame f;
  ASSERT_TRUE(page.next(text, f));
  EXPECT_EQ(text, R"({"type":"hello"})");
  // The "visual thread": publishes a frame every 10 ms until the page has seen one.
  std::atomic<bool> done{false};
  std::thread visual([&] {
    const std::vector<float> xyz{1, 2, 3, 4, 5, 6};
    for (int k = 0; !done.load() && k < 30000; ++k) {
      server.publish(xyz, Vec3(0, 0, 0.5), Vec3(0.1, 0.2, 0.3));
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  f = page.next_frame();
  EXPECT_EQ(f.xyz, (std::vector<float>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(f.force, Vec3(0, 0, 0.5));
  // Probe targets: stored into the SeqLock, clamped into the box; bad messages refused, not fatal.
  page.send_text("not json");
  page.move_probe(Vec3(0.25, -0.5, 7.0));
  const auto until = Clock::now() + std::chrono::seconds(60);
  while (server.stats().probe_moves < 1 && Clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const ProbeSample s = probe.load();
  EXPECT_EQ(s.x[0], 0.25);
  EXPECT_EQ(s.x[1], -0.5);
  EXPECT_EQ(s.x[2], 1.0);
  EXPECT_GE(server.stats().refused, 1);
  f = page.next_frame();  // still connected after the bad message
  done = true;
  visual.join();
  EXPECT_GE(server.stats().frames_sent, 2);
  EXPECT_EQ(server.stats().pages, 1);
  server.stop();
  server.stop();  // idempotent
}

TEST_F(LiveServerTest, ForeignOriginCannotConnect) {
  SeqLock<ProbeSample> probe;
  LiveServer server(options(), probe);
  EXPECT_THROW(Page(server.port(), "http://evil.example"), boost::system::system_error);
  EXPECT_EQ(server.stats().pages, 0);
}

// The whole chain on the liver case: loop (interactive probe) -> visual thread -> server -> page,
// and page -> server -> SeqLock -> haptic and control threads. The probe starts 2 mm above the
// surface (no contact: zero force); moved 10 mm into the liver, the frames' force must grow.
TEST(LiveServerLiver, AProbeMoveThroughTheWebSocketChangesTheForce) {
  const RealtimeCase c = load_realtime_case(
      (fs::path(TMLAB_SOURCE_DIR) / "cases" / "realtime" / "liver-poke.json").string(), TMLAB_SOURCE_DIR);
  auto control = c.make_control();
  SeqLock<ProbeSample> target(ProbeSample{0.0, {c.probe_start.x(), c.probe_start.y(), c.probe_start.z()}});
  LiveServerOptions so;
  so.port = 0;
  so.probe_box = probe_box(c.mesh, 2.0 * c.control.probe_radius);
  so.hello = hello_message(c.mesh, c.control.probe_radius, c.probe_start, so.probe_box, c.name, c.visual_hz);
  so.nodes = static_cast<int>(c.mesh.num_points());
  LiveServer server(std::move(so), target);

  std::atomic<bool> stop{false};
  LoopOptions lo;
  lo.duration = 600.0;
  lo.haptic_hz = c.haptic_hz;
  lo.visual_hz = c.visual_hz;
  lo.interactive = &target;
  lo.keep_log = false;
  lo.timing_window = 5.0;
  lo.on_frame = [&server](const std::vector<float>& xyz, const Vec3& f, const Vec3& x) {
    server.publish(xyz, f, x);
  };
  lo.stop = &stop;
  LoopResult result;
  std::thread loop([&] { result = run_realtime_loop(*control, lo); });

  Page page(server.port());
  std::string text;
  LiveFrame f;
  ASSERT_TRUE(page.next(text, f));
  const auto hello = nlohmann::json::parse(text);
  EXPECT_EQ(hello["nodes"], c.mesh.num_points());
  f = page.next_frame();
  ASSERT_EQ(f.xyz.size(), 3u * static_cast<std::size_t>(c.mesh.num_points()));
  EXPECT_EQ(f.force.norm(), 0.0) << "the probe starts clear of the liver";
  EXPECT_NEAR((f.probe - c.probe_start).norm(), 0.0, 1e-6);

  const Vec3 pressed = c.probe_start + 0.012 * c.direction;  // 10 mm past the surface
  page.move_probe(pressed);
  const auto until = Clock::now() + std::chrono::seconds(120);
  double peak = 0.0;
  while (Clock::now() < until) {
    f = page.next_frame();
    peak = std::max(peak, f.force.norm());
    if ((f.probe - pressed).norm() < 1e-6 && f.force.norm() > 0.05) break;
  }
  stop = true;
  loop.join();
  server.stop();
  EXPECT_NEAR((f.probe - pressed).norm(), 0.0, 1e-6) << "the probe target reached the loop";
  EXPECT_GT(f.force.norm(), 0.05) << "peak seen " << peak << " N";
  EXPECT_LT(f.force.dot(c.direction), 0.0) << "the liver pushes the probe back";
  EXPECT_GT(result.haptic.iterations, 0);
  EXPECT_GT(server.stats().frames_sent, 1);
}

}  // namespace

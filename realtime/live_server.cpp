// The one Boost.Beast translation unit of tmlab::realtime (live_server.hpp). One io_context, run by
// one thread: every handler below runs on that thread, so the session list and the encoded frame
// need no lock. The only data shared with other threads are the frame TripleBuffer (visual thread
// writes), the probe SeqLock (this thread writes) and the statistics (relaxed atomics).
#include "realtime/live_server.hpp"

#include "core/base/error.hpp"
#include "realtime/triple_buffer.hpp"

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

namespace tmlab::rt {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

class WsSession;

}  // namespace

struct LiveServer::Impl {
  Impl(LiveServerOptions o, SeqLock<ProbeSample>& p)
      : opt(std::move(o)), probe(p), frames([&] {
          LiveFrame proto;
          proto.xyz.assign(3 * static_cast<std::size_t>(std::max(0, opt.nodes)), 0.0f);
          return proto;
        }()) {}

  LiveServerOptions opt;
  SeqLock<ProbeSample>& probe;
  net::io_context ioc{1};
  tcp::acceptor acceptor{ioc};
  net::steady_timer tick{ioc}, grace{ioc};
  TripleBuffer<LiveFrame> frames;
  std::vector<std::weak_ptr<WsSession>> sessions;  // server thread only
  std::string host_ok[2];                          // accepted Host headers
  std::string origin_ok[2];                        // accepted Origin headers
  int port = 0;
  std::thread thread;
  std::atomic<bool> stopping{false};
  const std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  std::uint32_t next_index = 0;  // publisher only
  std::atomic<long> published{0}, sent{0}, skipped{0}, moves{0}, refused{0}, pages{0};

  void log(const std::string& m) const {
    if (opt.log) opt.log(m);
  }
  void refuse(const std::string& why) {
    refused.fetch_add(1, std::memory_order_relaxed);
    log("refused: " + why);
  }
  bool host_allowed(beast::string_view h) const { return h == host_ok[0] || h == host_ok[1]; }
  bool origin_allowed(beast::string_view o) const { return o == origin_ok[0] || o == origin_ok[1]; }
  void do_accept();
  void on_tick();
  void shutdown();
};

namespace {

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket&& s, LiveServer::Impl& srv) : ws_(std::move(s)), srv_(srv) {}

  void run(http::request<http::string_body> req) {
    beast::get_lowest_layer(ws_).expires_never();
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(64 * 1024);  // a probe message is ~60 bytes
    ws_.async_accept(req, [self = shared_from_this()](beast::error_code ec) { self->on_accept(ec); });
  }

  /// Sends `frame` unless the previous write is still under way (then this page skips it).
  void send(const std::shared_ptr<const std::vector<std::uint8_t>>& frame) {
    if (!open_) return;
    if (writing_) {
      srv_.skipped.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    writing_ = true;
    out_ = frame;
    ws_.binary(true);
    ws_.async_write(net::buffer(*out_), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (!ec) self->srv_.sent.fetch_add(1, std::memory_order_relaxed);
      self->write_done();
    });
  }

  /// Closes the connection (going away); after the write under way, if any: Beast allows one
  /// write-type operation (write or close) at a time.
  void close() {
    if (!open_) return;
    open_ = false;
    if (writing_)
      close_after_write_ = true;
    else
      do_close();
  }

 private:
  void write_done() {
    writing_ = false;
    if (close_after_write_) do_close();
  }
  void do_close() {
    close_after_write_ = false;
    ws_.async_close(websocket::close_code::going_away, [self = shared_from_this()](beast::error_code) {});
  }

  void on_accept(beast::error_code ec) {
    if (ec) return srv_.refuse("WebSocket handshake: " + ec.message());
    if (srv_.stopping.load()) return;
    open_ = true;
    srv_.pages.fetch_add(1, std::memory_order_relaxed);
    srv_.sessions.push_back(weak_from_this());
    srv_.log("page connected");
    writing_ = true;  // the hello goes first: frames wait for it
    ws_.text(true);
    ws_.async_write(net::buffer(srv_.opt.hello),
                    [self = shared_from_this()](beast::error_code e, std::size_t) {
                      if (e) self->open_ = false;
                      self->write_done();
                    });
    do_read();
  }

  void do_read() {
    ws_.async_read(in_,
                   [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec) {
    if (ec) {  // closed by the page, or by stop()
      if (open_) srv_.log("page disconnected");
      open_ = false;
      return;
    }
    const std::string text = beast::buffers_to_string(in_.data());
    in_.consume(in_.size());
    std::string error;
    const std::optional<Vec3> x =
        ws_.got_text() ? parse_probe_message(text, srv_.opt.probe_box, error) : std::optional<Vec3>{};
    if (x) {
      const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - srv_.t0).count();
      srv_.probe.store(ProbeSample{t, {x->x(), x->y(), x->z()}});
      srv_.moves.fetch_add(1, std::memory_order_relaxed);
    } else {
      srv_.refuse("page message: " + (ws_.got_text() ? error : std::string("binary message")));
    }
    do_read();
  }

  websocket::stream<beast::tcp_stream> ws_;
  LiveServer::Impl& srv_;
  beast::flat_buffer in_;
  std::shared_ptr<const std::vector<std::uint8_t>> out_;
  bool writing_ = false, open_ = false, close_after_write_ = false;
};

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& s, LiveServer::Impl& srv) : stream_(std::move(s)), srv_(srv) {}

  void run() { do_read(); }

 private:
  void do_read() {
    req_ = {};
    parser_.emplace();
    parser_->body_limit(4096);  // the page sends no bodies
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec) {
    if (ec == http::error::end_of_stream) return close();
    if (ec) return;  // timeout, reset, malformed request: drop the connection
    req_ = parser_->release();
    if (!srv_.host_allowed(req_[http::field::host])) {
      srv_.refuse("HTTP Host '" + std::string(req_[http::field::host]) + "'");
      return send_text(http::status::forbidden, "forbidden host\n");
    }
    if (websocket::is_upgrade(req_)) {
      const auto origin = req_[http::field::origin];
      if (req_.target() != "/ws" || (!origin.empty() && !srv_.origin_allowed(origin)) ||
          srv_.stopping.load()) {
        srv_.refuse("WebSocket upgrade for '" + std::string(req_.target()) + "' from origin '" +
                    std::string(origin) + "'");
        return send_text(http::status::forbidden, "forbidden\n");
      }
      stream_.expires_never();
      std::make_shared<WsSession>(stream_.release_socket(), srv_)->run(std::move(req_));
      return;
    }
    if (req_.method() != http::verb::get && req_.method() != http::verb::head)
      return send_text(http::status::method_not_allowed, "GET or HEAD only\n");
    const std::optional<std::filesystem::path> file =
        srv_.opt.files.resolve(std::string_view(req_.target().data(), req_.target().size()));
    if (!file) {
      srv_.refuse("no file for '" + std::string(req_.target()) + "'");
      return send_text(http::status::not_found, "not found\n");
    }
    http::file_body::value_type body;
    beast::error_code fec;
    body.open(file->c_str(), beast::file_mode::scan, fec);
    if (fec) return send_text(http::status::not_found, "not found\n");
    const auto size = body.size();
    http::response<http::file_body> res{std::piecewise_construct, std::make_tuple(std::move(body)),
                                        std::make_tuple(http::status::ok, req_.version())};
    res.set(http::field::content_type, StaticFiles::content_type(*file));
    res.set(http::field::cache_control, "no-store");
    res.set("X-Content-Type-Options", "nosniff");
    res.content_length(size);
    res.keep_alive(req_.keep_alive());
    if (req_.method() == http::verb::head) {
      http::response<http::empty_body> head{http::status::ok, req_.version()};
      head.set(http::field::content_type, StaticFiles::content_type(*file));
      head.content_length(size);
      head.keep_alive(req_.keep_alive());
      return send(std::move(head));
    }
    send(std::move(res));
  }

  void send_text(http::status status, const std::string& text) {
    http::response<http::string_body> res{status, req_.version()};
    res.set(http::field::content_type, "text/plain; charset=utf-8");
    res.body() = text;
    res.prepare_payload();
    res.keep_alive(false);
    send(std::move(res));
  }

  template <class Body>
  void send(http::response<Body>&& r) {
    auto sp = std::make_shared<http::response<Body>>(std::move(r));
    http::async_write(stream_, *sp, [self = shared_from_this(), sp](beast::error_code ec, std::size_t) {
      if (ec || sp->need_eof()) return self->close();
      self->do_read();
    });
  }

  void close() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  }

  beast::tcp_stream stream_;
  LiveServer::Impl& srv_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  http::request<http::string_body> req_;
};

}  // namespace

void LiveServer::Impl::do_accept() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket s) {
    if (ec || stopping.load()) return;  // closed by shutdown()
    std::make_shared<HttpSession>(std::move(s), *this)->run();
    do_accept();
  });
}

void LiveServer::Impl::on_tick() {
  if (stopping.load()) return;
  if (frames.update()) {
    auto encoded = std::make_shared<std::vector<std::uint8_t>>();
    encode_frame(frames.read_buffer(), *encoded);
    const std::shared_ptr<const std::vector<std::uint8_t>> frame = std::move(encoded);
    sessions.erase(std::remove_if(sessions.begin(), sessions.end(),
                                  [](const std::weak_ptr<WsSession>& w) { return w.expired(); }),
                   sessions.end());
    for (const auto& w : sessions)
      if (auto s = w.lock()) s->send(frame);
  }
  tick.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / opt.send_hz)));
  tick.async_wait([this](beast::error_code ec) {
    if (!ec) on_tick();
  });
}

void LiveServer::Impl::shutdown() {
  beast::error_code ec;
  acceptor.close(ec);
  tick.cancel();
  for (const auto& w : sessions)
    if (auto s = w.lock()) s->close();
  sessions.clear();
  // Pages get half a second to acknowledge the close; plain HTTP connections are not waited for.
  grace.expires_after(std::chrono::milliseconds(500));
  grace.async_wait([this](beast::error_code) { ioc.stop(); });
}

LiveServer::LiveServer(LiveServerOptions options, SeqLock<ProbeSample>& probe_target)
    : impl_(std::make_unique<Impl>(std::move(options), probe_target)) {
  Impl& s = *impl_;
  if (s.opt.port < 0 || s.opt.port > 65535)
    throw Error("--serve: port " + std::to_string(s.opt.port) + " is not in 0..65535");
  if (!(s.opt.send_hz > 0.0)) throw Error("live server: send_hz must be > 0");
  const tcp::endpoint ep(net::ip::make_address_v4("127.0.0.1"), static_cast<unsigned short>(s.opt.port));
  beast::error_code ec;
  s.acceptor.open(ep.protocol(), ec);
  if (!ec)
    s.acceptor.set_option(net::socket_base::reuse_address(true), ec);  // TIME_WAIT only, not a listener
  if (!ec) s.acceptor.bind(ep, ec);
  if (ec == net::error::address_in_use)
    throw Error("--serve: port " + std::to_string(s.opt.port) +
                " on 127.0.0.1 is already in use (another tmlab --serve?); choose another with --port P, "
                "or --port 0 for any free port");
  if (!ec) s.acceptor.listen(net::socket_base::max_listen_connections, ec);
  if (ec)
    throw Error("--serve: cannot listen on 127.0.0.1:" + std::to_string(s.opt.port) + ": " + ec.message());
  s.port = s.acceptor.local_endpoint().port();
  const std::string p = std::to_string(s.port);
  s.host_ok[0] = "127.0.0.1:" + p;
  s.host_ok[1] = "localhost:" + p;
  s.origin_ok[0] = "http://" + s.host_ok[0];
  s.origin_ok[1] = "http://" + s.host_ok[1];
  s.do_accept();
  s.on_tick();
  s.thread = std::thread([&s] {
    for (;;) {
      try {
        s.ioc.run();
        return;
      } catch (const std::exception& e) {  // a handler threw: log it and keep serving
        s.log(std::string("server error: ") + e.what());
      }
    }
  });
}

LiveServer::~LiveServer() { stop(); }

int LiveServer::port() const { return impl_->port; }

void LiveServer::publish(const std::vector<float>& xyz, const Vec3& force, const Vec3& probe) {
  Impl& s = *impl_;
  LiveFrame& f = s.frames.write_buffer();
  if (xyz.size() != f.xyz.size()) return;  // not this mesh: nothing sensible to send
  std::copy(xyz.begin(), xyz.end(), f.xyz.begin());
  f.index = s.next_index++;
  f.t = std::chrono::duration<double>(std::chrono::steady_clock::now() - s.t0).count();
  f.force = force;
  f.probe = probe;
  s.frames.publish();
  s.published.fetch_add(1, std::memory_order_relaxed);
}

void LiveServer::stop() {
  Impl& s = *impl_;
  if (s.stopping.exchange(true)) return;
  net::post(s.ioc, [&s] { s.shutdown(); });
  if (s.thread.joinable()) s.thread.join();
}

LiveServerStats LiveServer::stats() const {
  const Impl& s = *impl_;
  LiveServerStats r;
  r.frames_published = s.published.load();
  r.frames_sent = s.sent.load();
  r.frames_skipped = s.skipped.load();
  r.probe_moves = s.moves.load();
  r.refused = s.refused.load();
  r.pages = s.pages.load();
  return r;
}

}  // namespace tmlab::rt

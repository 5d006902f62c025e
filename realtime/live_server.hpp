// The server of `tmlab realtime --serve` (docs/realtime.md, "The live page"): HTTP for the page's
// files and one WebSocket endpoint (/ws) on 127.0.0.1 only, run by ONE thread of its own
// (Boost.Beast/Asio, kept in live_server.cpp alone: no Boost header leaks into other sources).
//
// It never disturbs the real-time threads:
//   - frames: the visual thread calls publish(), which copies the node positions into the write
//     buffer of a TripleBuffer<LiveFrame> sized at construction and publishes it (no lock, no
//     allocation). The server thread takes the newest frame every 1/send_hz, encodes it once and
//     sends it to every page; a page still busy with the previous frame skips this one (a slow
//     browser drops frames, it never slows the loop).
//   - probe: the page's probe target (live_protocol.hpp) is checked, clamped into the probe box
//     and stored into the SeqLock<ProbeSample> the haptic thread reads (LoopOptions::interactive);
//     the server thread is its only writer.
// Requests are checked: Host must name the loopback server and a WebSocket's Origin (when sent) the
// page itself, so another web site open in the browser can neither read nor steer the run (DNS
// rebinding, cross-site WebSocket); files come only from the mounted directories (static_files.hpp).
#pragma once

#include "realtime/live_protocol.hpp"
#include "realtime/realtime_loop.hpp"
#include "realtime/seqlock.hpp"
#include "realtime/static_files.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tmlab::rt {

struct LiveServerOptions {
  int port = 8765;    ///< on 127.0.0.1; 0: any free port (port() says which)
  StaticFiles files;  ///< what HTTP may serve
  std::string hello;  ///< the text message a page gets first (hello_message())
  Box probe_box;      ///< probe targets are clamped into it
  int nodes = 0;      ///< nodes per frame
  double send_hz = 60.0;
  /// Messages of the server thread (connections, refused input). May be empty.
  std::function<void(const std::string&)> log;
};

struct LiveServerStats {
  long frames_published = 0;  ///< publish() calls
  long frames_sent = 0;       ///< WebSocket frame messages written (all pages)
  long frames_skipped = 0;    ///< frames a busy page did not get
  long probe_moves = 0;       ///< accepted probe messages
  long refused = 0;           ///< refused messages and requests
  long pages = 0;             ///< WebSocket connections accepted so far
};

class LiveServer {
 public:
  /// Listens on 127.0.0.1:port and starts the server thread. Throws tmlab::Error when the port is
  /// taken or cannot be bound (naming it).
  LiveServer(LiveServerOptions options, SeqLock<ProbeSample>& probe_target);
  ~LiveServer();  ///< stop()
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const;
  /// One writer thread (the visual thread): no lock, no allocation. xyz.size() must be 3 nodes.
  void publish(const std::vector<float>& xyz, const Vec3& force, const Vec3& probe);
  /// Closes the pages and the listener and joins the server thread (idempotent).
  void stop();
  LiveServerStats stats() const;

  struct Impl;  ///< the Beast side (live_server.cpp only)

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace tmlab::rt

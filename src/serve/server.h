// The HTTP side of rad serve: the page, its event stream, the mesh buffers, edits and exports.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "serve/session.h"
#include "serve/web_assets.h"

namespace rad {

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;   // 0: any free port
  int threads = 16;  // requests served at once; each open page holds one for its event stream
};

/// True for 127.0.0.0/8, ::1 and localhost.
bool is_loopback_host(std::string_view host);

/// Serves one Session over HTTP (cpp-httplib). Routes:
///   GET  /, /index.html, /app.js, /style.css, /vendor/...   the page (WebAssets, exact paths)
///   GET  /api/scene      objects, bounds, default camera (JSON)
///   GET  /api/status     the latest snapshot's status (JSON)
///   GET  /api/events     server-sent events: one "snapshot" event (status JSON) per snapshot
///   GET  /api/mesh       positions, colours, indices, face polygons (binary, see responses.h)
///   GET  /api/colours    colours only (binary)
///   POST /api/material /api/subdivide /api/pause /api/resume /api/restart /api/exposure
///   GET  /api/export.{ply,off,obj,gltf,glb,png}   the current snapshot as a download
/// Every POST needs Content-Type: application/json; bad input answers 400 with
/// {"error": "..."}; a full edit queue 503, and so do event streams beyond half the pool (each
/// holds a thread); a request sent or read slower than 3 s is dropped. When bound to loopback,
/// requests whose Host header names another host are refused (403), so other web sites cannot
/// reach the server.
///
/// Threading: handlers run on the server's pool and only read immutable snapshots or queue
/// edits (see Session); a client that goes away ends its event stream at the next write.
class Server {
 public:
  Server(Session& session, WebAssets assets, const ServerOptions& o);
  ~Server();  // stop()
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  /// Binds the socket; returns the port (useful with port 0). Throws rad::Error when the
  /// address cannot be bound.
  int bind();
  /// Serves on a thread of its own until stop(). Ignores SIGPIPE process-wide (a client closing
  /// its connection must not end rad).
  void start();
  /// Ends the event streams, stops listening and joins. Idempotent.
  void stop();
  /// "http://host:port/" once bound.
  std::string url() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rad

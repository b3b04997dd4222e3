#include "serve/server.h"

#include <fmt/format.h>
#include <httplib.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "export/camera.h"
#include "export/image_file.h"
#include "export/image_render.h"
#include "export/mesh_file.h"
#include "serve/requests.h"
#include "serve/responses.h"

namespace rad {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr auto kEventPoll = std::chrono::milliseconds(250);  // how soon a stream sees stop()
constexpr auto kKeepAlive = std::chrono::seconds(2);         // how soon a lost client is noticed

void send_json(httplib::Response& res, int status, const std::string& body) {
  res.status = status;
  res.set_content(body, "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, status, nlohmann::json{{"error", message}}.dump());
}

std::string file_stem(const std::string& scene_name) {
  std::string s;
  for (char c : scene_name) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') {
      s += c;
    } else if (!s.empty() && s.back() != '_') {
      s += '_';
    }
  }
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s.empty() ? "rad" : s;
}

}  // namespace

bool is_loopback_host(std::string_view host) {
  return host == "localhost" || host == "::1" || host == "[::1]" || host.starts_with("127.");
}

struct Server::Impl {
  Session& session;
  WebAssets assets;
  ServerOptions options;
  std::string scene;  // /api/scene, fixed
  httplib::Server http;
  std::thread thread;
  std::atomic<bool> stopping{false};
  std::atomic<uint64_t> export_counter{0};
  // Each open event stream holds a pool thread: at most half the pool, so requests always find
  // one free whatever the number of pages (or hostile clients) left open.
  std::atomic<int> streams{0};
  int max_streams = 1;
  int port = -1;

  Impl(Session& s, WebAssets a, const ServerOptions& o)
      : session(s), assets(std::move(a)), options(o) {
    const auto snap = session.snapshot();
    const Camera camera = default_camera(snap->mesh.position(), snap->mesh.indices(), 1.0f);
    scene = scene_json(session.hierarchy(), camera, session.options().solver.converge);
    const int threads = std::max(2, o.threads);
    http.new_task_queue = [threads] { return new httplib::ThreadPool(size_t(threads)); };
    max_streams = std::max(1, threads / 2);
    http.set_keep_alive_timeout(2);
    // A client that sends its request slowly, or reads its answer slowly, holds a pool thread:
    // let go of it after 3 s.
    http.set_read_timeout(3, 0);
    http.set_write_timeout(3, 0);
    http.set_payload_max_length(64 * 1024);
    routes();
  }

  bool host_allowed(const httplib::Request& req) const {
    if (!is_loopback_host(options.host) || !req.has_header("Host")) return true;
    const std::string host = req.get_header_value("Host");
    for (const char* name : {"127.0.0.1", "localhost", "[::1]"}) {
      if (host == fmt::format("{}:{}", name, port) || (port == 80 && host == name)) return true;
    }
    return host == fmt::format("{}:{}", options.host, port);
  }

  /// Runs `f`, mapping what it throws to a JSON error: BadRequest and rad::Error are the
  /// client's (400), anything else is rad's (500).
  template <class F>
  httplib::Server::Handler guarded(F f) {
    return [f](const httplib::Request& req, httplib::Response& res) {
      try {
        f(req, res);
      } catch (const BadRequest& e) {
        send_error(res, 400, e.what());
      } catch (const Error& e) {
        send_error(res, 400, e.message());
      } catch (const std::exception& e) {
        send_error(res, 500, fmt::format("internal error: {}", e.what()));
      }
    };
  }

  /// A POST that queues an edit: 202 when queued, 503 when the queue is full.
  template <class F>
  void post(const char* path, F edit) {
    http.Post(
        path, guarded([this, edit](const httplib::Request& req, httplib::Response& res) {
          const std::string type = req.get_header_value("Content-Type");
          if (!type.starts_with("application/json")) {
            send_error(res, 415, "expected Content-Type: application/json");
            return;
          }
          if (!edit(req.body)) {
            send_error(res, 503, "too many edits are waiting for the solver; try again shortly");
            return;
          }
          send_json(
              res, 202,
              nlohmann::json{{"queued", true}, {"version", session.snapshot()->version}}.dump());
        }));
  }

  void routes() {
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (host_allowed(req)) return httplib::Server::HandlerResponse::Unhandled;
      send_error(res, 403, "this server only answers requests addressed to " + options.host);
      return httplib::Server::HandlerResponse::Handled;
    });
    http.set_error_handler(
        httplib::Server::HandlerWithResponse([](const httplib::Request&, httplib::Response& res) {
          if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
          send_error(res, res.status, res.status == 404 ? "not found" : "request failed");
          return httplib::Server::HandlerResponse::Handled;
        }));
    http.set_exception_handler([](const httplib::Request&, httplib::Response& res,
                                  std::exception_ptr) { send_error(res, 500, "internal error"); });

    http.Get("/api/scene", [this](const httplib::Request&, httplib::Response& res) {
      send_json(res, 200, scene);
    });
    http.Get("/api/status", [this](const httplib::Request&, httplib::Response& res) {
      send_json(res, 200, status_json(session.hierarchy(), *session.snapshot()));
    });
    http.Get("/api/events",
             [this](const httplib::Request&, httplib::Response& res) { events(res); });
    http.Get("/api/mesh", [this](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-store");
      res.set_content(mesh_buffer(*session.snapshot()), "application/octet-stream");
    });
    http.Get("/api/colours", [this](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-store");
      res.set_content(colour_buffer(*session.snapshot()), "application/octet-stream");
    });
    http.Get(R"(/api/export\.([a-z]+))",
             guarded([this](const httplib::Request& req, httplib::Response& res) {
               export_file(parse_export_request(req.matches[1].str(), req.params), res);
             }));

    post("/api/material", [this](const std::string& body) {
      const MaterialRequest r = parse_material_request(body, session.hierarchy());
      return session.edit_material(r.object, r.patch);
    });
    post("/api/light", [this](const std::string& body) {
      const LightRequest r = parse_light_request(body, session.hierarchy());
      return session.edit_light(r.light, r.patch);
    });
    post("/api/subdivide", [this](const std::string& body) {
      return session.subdivide(parse_subdivide_request(body, session.hierarchy()));
    });
    post("/api/restart",
         [this](const std::string& body) { return session.restart(parse_restart_request(body)); });
    post("/api/exposure", [this](const std::string& body) {
      const ExposureRequest r = parse_exposure_request(body);
      return session.set_exposure(r.stops, r.refit);
    });
    post("/api/dimmers", [this](const std::string& body) {
      return session.set_dimmers(
          parse_dimmers_request(body, light_groups_kept(session.hierarchy()).size()));
    });
    post("/api/pause", [this](const std::string&) { return session.pause(); });
    post("/api/resume", [this](const std::string&) { return session.resume(); });

    // The page: exact paths from the fixed table, nothing else.
    http.Get(R"(/.*)", [this](const httplib::Request& req, httplib::Response& res) {
      if (const WebFile* f = assets.find(req.path)) {
        res.set_header("Cache-Control", "no-cache");
        // Streamed from the table (which outlives the server) with its length: no copy, and
        // httplib does not recompress it per request (its brotli takes seconds on three.js).
        res.set_content_provider(f->body.size(), f->content_type,
                                 [f](size_t offset, size_t length, httplib::DataSink& sink) {
                                   return sink.write(f->body.data() + offset,
                                                     std::min(length, f->body.size() - offset));
                                 });
      } else {
        send_error(res, 404, "not found");
      }
    });
  }

  void events(httplib::Response& res) {
    if (streams.fetch_add(1) >= max_streams) {
      streams.fetch_sub(1);
      send_error(res, 503,
                 fmt::format("too many event streams open ({}); close a page", max_streams));
      return;
    }
    res.set_header("Cache-Control", "no-store");
    auto last = std::make_shared<uint64_t>(0);
    auto first = std::make_shared<bool>(true);
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, last, first](size_t, httplib::DataSink& sink) {
          if (*first) {
            *first = false;
            static constexpr char kRetry[] = "retry: 1000\n\n";
            if (!sink.write(kRetry, sizeof kRetry - 1)) return false;
          }
          const auto give_up = Clock::now() + kKeepAlive;
          while (!stopping && !session.stopped()) {
            const auto snap = session.wait_for_snapshot(*last, kEventPoll);
            if (snap->version > *last) {
              *last = snap->version;
              const std::string ev =
                  fmt::format("id: {}\nevent: snapshot\ndata: {}\n\n", snap->version,
                              status_json(session.hierarchy(), *snap));
              return sink.write(ev.data(), ev.size());
            }
            if (Clock::now() >= give_up) {
              static constexpr char kPing[] = ": keep-alive\n\n";
              return sink.write(kPing, sizeof kPing - 1);  // false once the client is gone
            }
          }
          sink.done();
          return true;
        },
        [this](bool) { streams.fetch_sub(1); });
  }

  void export_file(const ExportRequest& r, httplib::Response& res) {
    const auto snap = session.snapshot();
    const OutputMesh& mesh = snap->mesh;
    const fs::path path =
        fs::temp_directory_path() /
        fmt::format("rad-serve-{}-{}{}", ::getpid(), export_counter++, extension(r.format));
    struct Remove {
      fs::path p;
      ~Remove() {
        std::error_code ec;
        fs::remove(p, ec);
      }
    } remove{path};
    if (r.format == ExportFormat::Png) {
      const RenderOptions ro{r.width, r.height};
      const Camera camera = r.camera ? *r.camera
                                     : default_camera(mesh.position(), mesh.indices(),
                                                      float(r.width) / float(r.height));
      write_image_file(path.string(),
                       render_image(mesh.position(), mesh.display, mesh.indices(), camera, ro),
                       snap->tone);
    } else {
      MeshFileOptions mo;
      mo.tone = snap->tone;
      write_mesh_file(path.string(), mesh, mo);
    }
    std::ifstream in(path, std::ios::binary);
    std::ostringstream body;
    body << in.rdbuf();
    if (!in) throw std::runtime_error("cannot read back " + path.string());
    res.set_header("Content-Disposition", fmt::format("attachment; filename=\"{}-shot{}{}\"",
                                                      file_stem(session.hierarchy().scene_name),
                                                      snap->shots, extension(r.format)));
    res.set_header("Cache-Control", "no-store");
    res.set_content(body.str(), content_type(r.format));
  }
};

Server::Server(Session& session, WebAssets assets, const ServerOptions& o)
    : impl_(std::make_unique<Impl>(session, std::move(assets), o)) {}

Server::~Server() { stop(); }

int Server::bind() {
  Impl& m = *impl_;
  if (m.options.port == 0) {
    m.port = m.http.bind_to_any_port(m.options.host);
  } else if (m.http.bind_to_port(m.options.host, m.options.port)) {
    m.port = m.options.port;
  }
  if (m.port <= 0) {
    throw Error(fmt::format("cannot listen on {}:{} (in use, or not an address of this machine)",
                            m.options.host, m.options.port));
  }
  return m.port;
}

void Server::start() {
  std::signal(SIGPIPE, SIG_IGN);
  impl_->thread = std::thread([this] { impl_->http.listen_after_bind(); });
}

void Server::stop() {
  impl_->stopping = true;
  impl_->http.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

std::string Server::url() const {
  const std::string& host = impl_->options.host;
  const bool v6 = host.find(':') != std::string::npos && !host.starts_with("[");
  return fmt::format("http://{}{}{}:{}/", v6 ? "[" : "", host, v6 ? "]" : "", impl_->port);
}

}  // namespace rad

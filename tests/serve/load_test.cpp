// rad serve under load and abuse: concurrent clients, more event streams than threads, slow
// senders and readers, malformed and oversized requests, clients that vanish. The solver keeps
// shooting, good requests keep their answers, bad ones get a 4xx (or the connection is closed),
// and nothing ends the process.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "serve/server.h"
#include "serve_scene.h"

namespace rad {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;

// A raw TCP connection to the server, for what httplib's client will not send.
class Raw {
 public:
  explicit Raw(int port) : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(uint16_t(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ok_ = connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    timeval tv{5, 0};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~Raw() { close(fd_); }
  bool connected() const { return ok_; }
  void send_all(const std::string& s) {
    for (size_t at = 0; at < s.size();) {
      const ssize_t n = ::send(fd_, s.data() + at, s.size() - at, MSG_NOSIGNAL);
      if (n <= 0) return;
      at += size_t(n);
    }
  }
  // What the server answers until it closes or 5 s pass.
  std::string receive() {
    std::string out;
    char buf[4096];
    for (ssize_t n; (n = ::recv(fd_, buf, sizeof buf, 0)) > 0;) out.append(buf, size_t(n));
    return out;
  }

 private:
  int fd_;
  bool ok_ = false;
};

int status_code(const std::string& response) {
  return response.rfind("HTTP/1.1 ", 0) == 0 ? std::atoi(response.c_str() + 9) : 0;
}

class LoadTest : public ::testing::Test {
 protected:
  LoadTest()
      : h(build_hierarchy(testing::serve_scene())),
        vis(make_visibility_backend(BackendKind::Embree, h)) {
    SessionOptions o;
    o.solver = testing::serve_options();
    o.solver.converge = 1e-9;  // keeps shooting for the whole test
    session = std::make_unique<Session>(h, *vis, o);
    server = std::make_unique<Server>(*session, WebAssets{}, ServerOptions{"127.0.0.1", 0, 4});
    port = server->bind();
    session->start();
    server->start();
  }
  ~LoadTest() override {
    server->stop();
    session->stop();
  }
  int64_t shots() {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(10, 0);
    auto r = c.Get("/api/status");
    return r && r->status == 200 ? json::parse(r->body).at("shots").get<int64_t>() : -1;
  }

  const Hierarchy h;
  const std::unique_ptr<VisibilityBackend> vis;
  std::unique_ptr<Session> session;
  std::unique_ptr<Server> server;
  int port = 0;
};

TEST_F(LoadTest, ConcurrentClientsAllGetTheirAnswers) {
  std::atomic<int> ok{0}, bad{0};
  std::vector<std::thread> clients;
  for (int t = 0; t < 8; ++t) {
    clients.emplace_back([&] {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(20, 0);
      for (int i = 0; i < 20; ++i) {
        auto r = c.Get(i % 2 ? "/api/status" : "/api/colours");
        (r && r->status == 200 ? ok : bad)++;
      }
    });
  }
  for (std::thread& t : clients) t.join();
  EXPECT_EQ(ok.load(), 160);
  EXPECT_EQ(bad.load(), 0);
}

TEST_F(LoadTest, EventStreamsBeyondHalfThePoolAre503AndRequestsStillAnswer) {
  std::atomic<bool> done{false};
  std::atomic<int> streaming{0}, refused{0};
  std::vector<std::thread> streams;
  for (int i = 0; i < 6; ++i) {
    streams.emplace_back([&] {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(30, 0);
      bool counted = false;
      auto r = c.Get("/api/events", [&](const char* data, size_t n) {
        // A stream starts with its retry line; a refusal is a JSON error.
        if (!counted && std::string(data, n).rfind("retry:", 0) == 0) counted = true, streaming++;
        return !done.load();
      });
      if (r && r->status == 503) refused++;
    });
  }
  std::this_thread::sleep_for(1500ms);
  const auto t = std::chrono::steady_clock::now();
  EXPECT_GE(shots(), 0) << "status answered while streams are open";
  EXPECT_LT(std::chrono::steady_clock::now() - t, 2s);
  EXPECT_EQ(streaming.load(), 2) << "half of the 4 threads";
  EXPECT_EQ(refused.load(), 4);
  done = true;
  for (std::thread& s : streams) s.join();
}

TEST_F(LoadTest, MalformedOversizedSlowAndVanishingClientsLeaveTheSolverRunning) {
  const int64_t before = shots();
  ASSERT_GE(before, 0);
  {  // Not HTTP at all.
    Raw r(port);
    ASSERT_TRUE(r.connected());
    static constexpr char kGarbage[] = "\x00\x01\x02 garbage \xff\xfe\r\n\r\n";
    r.send_all(std::string(kGarbage, sizeof kGarbage - 1));
    const std::string a = r.receive();
    EXPECT_TRUE(a.empty() || (status_code(a) >= 400 && status_code(a) < 500)) << a.substr(0, 80);
  }
  {  // A header line of 100 kB.
    Raw r(port);
    r.send_all("GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Big: " + std::string(100000, 'a') +
               "\r\n\r\n");
    const std::string a = r.receive();
    EXPECT_TRUE(a.empty() || (status_code(a) >= 400 && status_code(a) < 500)) << a.substr(0, 80);
  }
  {  // A body of 1 MB, over the 64 kB limit.
    httplib::Client c("127.0.0.1", port);
    auto res = c.Post("/api/material", std::string(1 << 20, '{'), "application/json");
    EXPECT_TRUE(!res || res->status == 413) << (res ? res->status : 0);
  }
  {  // A body that is not JSON, and JSON that is not an edit.
    httplib::Client c("127.0.0.1", port);
    auto res = c.Post("/api/material", "{\"object\": [[[", "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400);
    res = c.Post("/api/material", "[1, 2, 3]", "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400);
  }
  {  // Slow senders: half a request each, never finished, on three connections of four threads.
    std::vector<std::unique_ptr<Raw>> slow;
    for (int i = 0; i < 3; ++i) {
      slow.push_back(std::make_unique<Raw>(port));
      slow.back()->send_all("GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ");
    }
    const auto t = std::chrono::steady_clock::now();
    EXPECT_GE(shots(), 0);
    EXPECT_LT(std::chrono::steady_clock::now() - t, 5s);
  }
  {  // A slow reader: asks for the mesh and reads nothing, then vanishes.
    Raw r(port);
    r.send_all("GET /api/mesh HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
    std::this_thread::sleep_for(200ms);
  }
  for (int i = 0; i < 10; ++i) {  // Clients that hang up mid-stream.
    httplib::Client c("127.0.0.1", port);
    c.Get("/api/events", [](const char*, size_t) { return false; });
  }
  std::this_thread::sleep_for(500ms);
  const int64_t after = shots();
  EXPECT_GT(after, before) << "the solver kept shooting";
}

}  // namespace
}  // namespace rad

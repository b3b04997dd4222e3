// The HTTP server over a running session: the page's fixed files only, 400s with a JSON message
// for bad input, binary buffers that agree with the status, events, exports, and clients that
// vanish mid-stream.
#include "serve/server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "serve/responses.h"
#include "serve_scene.h"

namespace rad {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
namespace fs = std::filesystem;

// Stand-ins for the npm modules: the server only needs the files to exist.
std::string fake_modules() {
  const fs::path root = fs::path(RAD_BINARY_DIR) / "tests" / "serve" / "fake_node_modules";
  for (const char* f :
       {"three/build/three.module.js", "three/build/three.core.js",
        "three/examples/jsm/controls/OrbitControls.js", "lil-gui/dist/lil-gui.esm.min.js"}) {
    fs::create_directories((root / f).parent_path());
    std::ofstream(root / f) << "// stand-in for " << f << "\n";
  }
  return root.string();
}

class ServerTest : public ::testing::Test {
 protected:
  ServerTest()
      : h(build_hierarchy(testing::serve_scene())),
        vis(make_visibility_backend(BackendKind::Embree, h)) {
    SessionOptions o;
    o.solver = testing::serve_options();
    session = std::make_unique<Session>(h, *vis, o);
    server = std::make_unique<Server>(*session, load_web_assets(fake_modules()),
                                      ServerOptions{"127.0.0.1", 0, 4});
    port = server->bind();
    session->start();
    server->start();
    client = std::make_unique<httplib::Client>("127.0.0.1", port);
    client->set_read_timeout(10, 0);
  }
  ~ServerTest() override {
    server->stop();
    session->stop();
  }
  httplib::Result post(const std::string& path, const std::string& body,
                       const char* type = "application/json") {
    return client->Post(path.c_str(), body, type);
  }
  static std::string error_of(const httplib::Result& r) {
    return json::parse(r->body).at("error").get<std::string>();
  }
  int32_t id(const std::string& name) const { return testing::object_named(h, name); }

  const Hierarchy h;
  const std::unique_ptr<VisibilityBackend> vis;
  std::unique_ptr<Session> session;
  std::unique_ptr<Server> server;
  std::unique_ptr<httplib::Client> client;
  int port = 0;
};

TEST_F(ServerTest, ServesThePageAndNothingElse) {
  auto r = client->Get("/");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->body.find("<canvas id=\"canvas\""), std::string::npos);
  EXPECT_EQ(r->get_header_value("Content-Type"), "text/html; charset=utf-8");
  r = client->Get("/vendor/three.module.js");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, "// stand-in for three/build/three.module.js\n");
  for (const char* path : {"/../../etc/passwd", "/vendor/../../../etc/passwd",
                           "/%2e%2e/%2e%2e/etc/passwd", "/vendor/three/package.json", "/app.js.map",
                           "/CMakeLists.txt", "/vendor/", "/api/nothing"}) {
    r = client->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
    EXPECT_EQ(error_of(r), "not found") << path;
  }
}

TEST_F(ServerTest, BadEditsGet400WithAMessage) {
  auto r = post("/api/material", "{\"object\": ");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r), "malformed JSON");
  r = post("/api/material", R"({"object": 1000, "emission": 1})");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r), "'object' is 1000; it must be in [0, 8]");
  r = post("/api/material", json{{"object", id("lamp")}, {"reflectivity", 3}}.dump());
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r), "'reflectivity' is 3; it must be in [0, 1]");
  r = post("/api/subdivide", R"({"polygon": -4})");
  EXPECT_EQ(r->status, 400);
  r = post("/api/pause", "{}", "text/plain");
  EXPECT_EQ(r->status, 415) << "a form on another site cannot send edits";
  r = post("/api/material", std::string(100 * 1024, ' '));
  EXPECT_EQ(r->status, 413);
  r = client->Get("/api/export.png?size=1x1");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r), "size: expected WxH, 16 to 4096 pixels each, got '1x1'");
  // Still alive and well.
  r = client->Get("/api/status");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
}

TEST_F(ServerTest, RefusesRequestsForOtherHosts) {
  auto r = client->Get("/api/status", {{"Host", "evil.example:80"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  r = client->Get("/api/status", {{"Host", "localhost:" + std::to_string(port)}});
  EXPECT_EQ(r->status, 200);
}

TEST_F(ServerTest, EditsAreQueuedAndShowInTheStatus) {
  auto r = post("/api/material", json{{"object", id("lamp")}, {"emission", 7.5}}.dump());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 202);
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  double emission = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const json st = json::parse(client->Get("/api/status")->body);
    emission = st["objects"][size_t(id("lamp"))]["emission"].get<double>();
    if (emission == 7.5) break;
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_EQ(emission, 7.5);
}

TEST_F(ServerTest, MeshAndColourBuffersAgreeWithEachOther) {
  const auto mesh = client->Get("/api/mesh");
  ASSERT_TRUE(mesh);
  ASSERT_GE(mesh->body.size(), 32u);
  uint32_t hdr[8];
  std::memcpy(hdr, mesh->body.data(), sizeof hdr);
  EXPECT_EQ(hdr[0], kMeshMagic);
  const size_t n = hdr[3], ni = hdr[4];
  ASSERT_GT(n, 0u);
  EXPECT_EQ(mesh->body.size(), 32 + 24 * n + 4 * ni + 4 * (ni / 3));
  std::vector<uint32_t> indices(ni);
  std::memcpy(indices.data(), mesh->body.data() + 32 + 24 * n, 4 * ni);
  for (uint32_t i : indices) ASSERT_LT(i, n);
  const auto colours = client->Get("/api/colours");
  ASSERT_TRUE(colours);
  std::memcpy(hdr, colours->body.data(), sizeof hdr);
  EXPECT_EQ(hdr[0], kColourMagic);
  EXPECT_EQ(colours->body.size(), 32 + 12 * size_t(hdr[3]));
}

TEST_F(ServerTest, ExportsTheCurrentSnapshot) {
  auto r = client->Get("/api/export.ply");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body.rfind("ply\n", 0), 0u);
  EXPECT_NE(r->get_header_value("Content-Disposition").find("serve_test_box-shot"),
            std::string::npos);
  r = client->Get("/api/export.png?size=64x48&camera=0.5,0.5,-2,0.5,0.5,0.5");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body.substr(1, 3), "PNG");
  r = client->Get("/api/export.glb");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->body.substr(0, 4), "glTF");
}

TEST_F(ServerTest, StreamsEventsAndForgetsClientsThatLeave) {
  std::string received;
  // Read until the first snapshot event, then hang up.
  auto r = client->Get("/api/events", [&](const char* data, size_t n) {
    received.append(data, n);
    return received.find("event: snapshot") == std::string::npos ||
           received.find("\n\n", received.find("event: snapshot")) == std::string::npos;
  });
  EXPECT_NE(received.find("retry: 1000"), std::string::npos);
  const size_t at = received.find("data: ");
  ASSERT_NE(at, std::string::npos);
  const json st = json::parse(received.substr(at + 6, received.find('\n', at) - at - 6));
  EXPECT_TRUE(st.contains("unshot_fraction"));
  // Many clients that vanish mid-stream leave the server answering.
  for (int i = 0; i < 12; ++i) {
    httplib::Client c("127.0.0.1", port);
    c.Get("/api/events", [](const char*, size_t) { return false; });
  }
  const auto t = std::chrono::steady_clock::now();
  auto status = client->Get("/api/status");
  ASSERT_TRUE(status);
  EXPECT_EQ(status->status, 200);
  EXPECT_LT(std::chrono::steady_clock::now() - t, 3s);
}

TEST_F(ServerTest, StopsPromptlyWithAnOpenEventStream) {
  std::thread listener([&] {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(30, 0);
    c.Get("/api/events", [](const char*, size_t) { return true; });
  });
  std::this_thread::sleep_for(300ms);
  const auto t = std::chrono::steady_clock::now();
  server->stop();
  EXPECT_LT(std::chrono::steady_clock::now() - t, 3s);
  listener.join();
}

// The box lit by a point light alone (the lamp quad emits nothing) and a directional light the
// scene left off, in a scene whose unit is 2 m: the page sees candela, the hierarchy holds
// candela per square unit.
TEST(LightEdits, TheSceneListsItsLightsAndTheirEditsContinueTheSolve) {
  Hierarchy h = build_hierarchy(testing::serve_scene(Vec3(0.0f)));
  Light bulb;
  bulb.name = "bulb";
  bulb.kind = LightKind::Point;
  bulb.position = Vec3(0.5f, 0.5f, 0.8f);
  bulb.direction = Vec3(0.0f, 0.0f, -1.0f);
  bulb.intensity = 1.0f;  // 4 cd at 2 m per unit
  Light sun;
  sun.name = "sun";
  sun.kind = LightKind::Directional;
  sun.direction = Vec3(0.0f, 0.0f, -1.0f);
  sun.intensity = 0.0f;
  // Where the bulb is, off in the scene: turned on, it lights the box as the bulb did.
  Light spare = bulb;
  spare.name = "spare";
  spare.intensity = 0.0f;
  h.lights = {bulb, sun, spare};
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SessionOptions o;
  o.solver = testing::serve_options();
  o.solver.converge = 1e-3;
  o.metres_per_unit = 2.0;
  Session session(h, *vis, o);
  Server server(session, load_web_assets(fake_modules()), ServerOptions{"127.0.0.1", 0, 4});
  httplib::Client client("127.0.0.1", server.bind());
  client.set_read_timeout(10, 0);
  session.start();
  server.start();
  auto post = [&](const json& body) {
    return client.Post("/api/light", body.dump(), "application/json");
  };
  auto status = [&] { return json::parse(client.Get("/api/status")->body); };
  // The status once converged after more than `shots` shots.
  auto converged_after = [&](int64_t shots) {
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    json st = status();
    while (std::chrono::steady_clock::now() < deadline &&
           !(st["status"] == "converged" && st["shots"].get<int64_t>() > shots)) {
      std::this_thread::sleep_for(20ms);
      st = status();
    }
    return st;
  };
  // The snapshot's radiosity integrated over its faces, per channel: linear in the light
  // whatever the mesh (a mean over vertices would follow where the solve subdivided).
  auto total_radiosity = [&] {
    const auto snap = session.snapshot();
    const MeshGeometry& g = *snap->mesh.geometry;
    DVec3 sum(0.0);
    for (size_t f = 0; f + 2 < g.indices.size(); f += 3) {
      const uint32_t a = g.indices[f], b = g.indices[f + 1], c = g.indices[f + 2];
      const double area = 0.5 * glm::length(glm::cross(g.position[b] - g.position[a],
                                                       g.position[c] - g.position[a]));
      sum += DVec3(snap->mesh.radiosity[a] + snap->mesh.radiosity[b] + snap->mesh.radiosity[c]) *
             (area / 3.0);
    }
    return sum;
  };

  const json scene = json::parse(client.Get("/api/scene")->body);
  ASSERT_EQ(scene["lights"].size(), 3u);
  EXPECT_EQ(scene["lights"][0]["name"], "bulb");
  EXPECT_EQ(scene["lights"][0]["kind"], "point");
  EXPECT_EQ(scene["lights"][0]["unit"], "cd");
  EXPECT_EQ(scene["lights"][1]["unit"], "lx");

  json st = converged_after(0);
  ASSERT_EQ(st["status"], "converged");
  EXPECT_NEAR(st["lights"][0]["intensity"].get<double>(), 4.0, 1e-5);
  EXPECT_EQ(st["lights"][0]["colour"], json::array({1.0, 1.0, 1.0}));
  const DVec3 white = total_radiosity();
  ASSERT_GT(white.x, 0.0);

  // Twice the intensity, an orange colour: red twice, blue half, continuing the same solve.
  int64_t shots = st["shots"].get<int64_t>();
  auto r = post({{"light", 0}, {"intensity", 8}, {"colour", {1.0, 0.5, 0.25}}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 202);
  st = converged_after(shots);
  ASSERT_EQ(st["status"], "converged");
  EXPECT_EQ(st["lights"][0]["intensity"].get<double>(), 8.0);
  EXPECT_EQ(st["lights"][0]["colour"], json::array({1.0, 0.5, 0.25}));
  EXPECT_NE(st["notice"].get<std::string>().find("light 'bulb'"), std::string::npos);
  const DVec3 orange = total_radiosity();
  EXPECT_NEAR(orange.x / white.x, 2.0, 0.02);
  EXPECT_NEAR(orange.z / white.z, 0.5, 0.005);

  // Off: nothing else lights the box.
  shots = st["shots"].get<int64_t>();
  r = post({{"light", 0}, {"intensity", 0}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 202);
  st = converged_after(shots);
  ASSERT_EQ(st["status"], "converged");
  EXPECT_EQ(st["lights"][0]["colour"], json::array({1.0, 0.5, 0.25})) << "kept for switching on";
  EXPECT_LT(std::abs(total_radiosity().x), 0.01 * white.x);

  // The spare bulb the scene leaves off (intensity 0) turned on at the bulb's 4 cd: the bulb's
  // light again.
  shots = st["shots"].get<int64_t>();
  r = post({{"light", 2}, {"intensity", 4}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 202) << r->body;
  st = converged_after(shots);
  ASSERT_EQ(st["status"], "converged");
  EXPECT_EQ(st["lights"][2]["intensity"].get<double>(), 4.0);
  const DVec3 spare_lit = total_radiosity();
  EXPECT_NEAR(spare_lit.x / white.x, 1.0, 0.02);
  EXPECT_NEAR(spare_lit.z / white.z, 1.0, 0.02);

  // Bad edits: 400 with a message, nothing queued.
  for (const json& bad :
       {json{{"light", 1}, {"intensity", -3}}, json{{"light", 3}, {"intensity", 1}},
        json{{"light", 0}, {"intensity", -1}}, json{{"light", 0}},
        json{{"light", 0}, {"colour", {2, 0, 0}}}, json{{"light", 0}, {"power", 3}}}) {
    r = post(bad);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << bad.dump();
    EXPECT_TRUE(json::parse(r->body).contains("error")) << bad.dump();
  }
  server.stop();
  session.stop();
}

TEST(WebAssets, SaysWhatIsMissingAndHowToInstallIt) {
  try {
    load_web_assets("/nonexistent/node_modules");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("/nonexistent/node_modules/three/build/three.module.js"), std::string::npos);
    EXPECT_NE(m.find("rad_install_web"), std::string::npos);
  }
}

TEST(LoopbackHost, KnowsTheLoopbackNames) {
  EXPECT_TRUE(is_loopback_host("127.0.0.1"));
  EXPECT_TRUE(is_loopback_host("localhost"));
  EXPECT_TRUE(is_loopback_host("::1"));
  EXPECT_FALSE(is_loopback_host("0.0.0.0"));
  EXPECT_FALSE(is_loopback_host("192.168.1.2"));
}

}  // namespace
}  // namespace rad

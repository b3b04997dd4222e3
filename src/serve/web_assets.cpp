#include "serve/web_assets.h"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "serve/page_files.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

struct VendorFile {
  const char* url;
  const char* path;  // under node_modules
};
// three.module.js imports ./three.core.js; OrbitControls imports "three" (the page's import
// map points it at /vendor/three.module.js).
constexpr VendorFile kVendor[] = {
    {"/vendor/three.module.js", "three/build/three.module.js"},
    {"/vendor/three.core.js", "three/build/three.core.js"},
    {"/vendor/OrbitControls.js", "three/examples/jsm/controls/OrbitControls.js"},
    {"/vendor/lil-gui.esm.js", "lil-gui/dist/lil-gui.esm.min.js"},
};

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  if (!in) throw Error(fmt::format("cannot read {}", p.string()));
  return s.str();
}

}  // namespace

const WebFile* WebAssets::find(std::string_view path) const {
  const auto it = files.find(path);
  return it == files.end() ? nullptr : &it->second;
}

std::string default_web_modules_dir() {
  if (const char* env = std::getenv("RAD_WEB_MODULES"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "web/node_modules" : (exe.parent_path() / "web" / "node_modules").string();
}

WebAssets load_web_assets(const std::string& modules_dir) {
  WebAssets a;
  for (const PageFile& f : page_files()) {
    a.files[f.url] = WebFile{f.content_type, std::string(f.data, f.size)};
  }
  a.files["/"] = a.files.at("/index.html");
  for (const VendorFile& v : kVendor) {
    const fs::path p = fs::path(modules_dir) / v.path;
    if (!fs::is_regular_file(p)) {
      throw Error(fmt::format(
          "rad serve needs three.js and lil-gui from npm, but {} is missing. Install them with "
          "`source tools/setup.sh && rad_install_web` (they go to web/node_modules beside the "
          "rad executable), or point RAD_WEB_MODULES at a node_modules folder that has them",
          p.string()));
    }
    a.files[v.url] = WebFile{"text/javascript; charset=utf-8", read_all(p)};
  }
  return a;
}

}  // namespace rad

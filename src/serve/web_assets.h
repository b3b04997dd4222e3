// The files the page is made of: its own (compiled into rad) and the three.js and lil-gui
// modules installed from npm. A fixed table: nothing else is ever served.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace rad {

struct WebFile {
  std::string content_type;
  std::string body;
};

/// URL path ("/", "/app.js", "/vendor/three.module.js", ...) -> file. Requests are looked up
/// here by exact path, so no request can name a file on disk.
struct WebAssets {
  std::map<std::string, WebFile, std::less<>> files;
  const WebFile* find(std::string_view path) const;
};

/// Where rad looks for node_modules: $RAD_WEB_MODULES when set, else web/node_modules beside
/// the rad executable (where tools/setup.sh's rad_install_web puts them).
std::string default_web_modules_dir();

/// The page plus the vendor modules read from `modules_dir`. Throws rad::Error naming the first
/// missing module file and how to install it.
WebAssets load_web_assets(const std::string& modules_dir);

}  // namespace rad

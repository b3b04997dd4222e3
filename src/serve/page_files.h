// The page's own files (src/serve/web), compiled into rad by embed_page.cmake.
#pragma once

#include <cstddef>
#include <span>

namespace rad {

struct PageFile {
  const char* url;  // "/index.html", "/app.js", "/style.css"
  const char* content_type;
  const char* data;
  size_t size;
};

/// Every page file, in a fixed order.
std::span<const PageFile> page_files();

}  // namespace rad

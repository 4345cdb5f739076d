// The browser UI (web/ and its npm packages), embedded at build time and served at /.
#pragma once

#include <string_view>

namespace spinfold::server {

struct WebAsset {
  std::string_view body;
  std::string_view content_type;
};

// The asset at a URL path ("/", "/app.js", "/vendor/uPlot.esm.js", …), or nullptr.
const WebAsset* web_asset(std::string_view path);

}  // namespace spinfold::server

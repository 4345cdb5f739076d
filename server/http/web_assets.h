// The browser UI (web/ and its npm packages), embedded at build time and served at /.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace spinfold::server {

struct WebAsset {
  std::string_view body;
  std::string_view content_type;
  std::string_view summary;  // the file's opening comment, for the route catalog
};

// Every embedded file by URL path ("/", "/main.js", "/vendor/uPlot.esm.js", …): the files of web/
// (cmake/embed_web.cmake, from a glob) and the npm files the page loads.
const std::map<std::string, WebAsset, std::less<>>& web_assets();

// The asset at a URL path, or nullptr.
const WebAsset* web_asset(std::string_view path);

}  // namespace spinfold::server

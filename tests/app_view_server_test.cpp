// rtdr view's server (app/view_server.h), without a socket: which request targets it routes at all, and which files
// it serves. The server itself, over HTTP, is tests/app_view_test.py's.
#include "app/view_server.h"
#include "cli_fixtures.h"
#include "core/error.h"

#include <catch2/catch.hpp>

#include <fstream>

namespace fs = std::filesystem;
using rtdr::view_request_allowed;

TEST_CASE("view_request_allowed routes plain paths and refuses '..' in any encoding, backslashes, '//' and non-paths") {
  // (target as sent, path as cpp-httplib decodes it once)
  for (const auto& [target, path] : std::vector<std::pair<std::string, std::string>>{
           {"/", "/"}, {"/view.js", "/view.js"}, {"/katex/fonts/KaTeX_Main-Regular.woff2", "/katex/fonts/KaTeX_Main-Regular.woff2"},
           {"/api/probe?frame=1&x=2&y=3&pass=atrous", "/api/probe"}, {"/a.b/c", "/a.b/c"}}) {
    INFO(target);
    CHECK(view_request_allowed(target, path));
  }
  for (const auto& [target, path] : std::vector<std::pair<std::string, std::string>>{
           {"/../etc/passwd", "/../etc/passwd"},
           {"/%2e%2e/etc/passwd", "/../etc/passwd"},
           {"/%252e%252e/etc/passwd", "/%2e%2e/etc/passwd"},  // encoded twice: a '%' is left after one decoding
           {"/katex/..%2f..%2fetc", "/katex/../../etc"},
           {"/view.js/..", "/view.js/.."},
           {"/..\\etc", "/..\\etc"},
           {"/%5cetc", "/\\etc"},
           {"//etc/passwd", "//etc/passwd"},
           {"http://127.0.0.1/index.html", "http://127.0.0.1/index.html"},
           {"*", "*"},
           {"", ""},
           {"/a%00b", std::string("/a\0b", 4)}}) {
    INFO(target);
    CHECK_FALSE(view_request_allowed(target, path));
  }
}

TEST_CASE("view_asset_routes lists the page's regular files and KaTeX's, never a subfolder or a symlink of the page") {
  const fs::path dir = rtdr::cli::scratch("rtdr_view_server_test", "assets");
  const fs::path page = dir / "page", katex = dir / "katex";
  fs::create_directories(page / "sub");
  fs::create_directories(katex / "fonts");
  for (const fs::path& p : {page / "index.html", page / "view.js", page / "sub" / "hidden.js", page / "notes.txt",
                            katex / "katex.min.js", katex / "katex.min.css", katex / "fonts" / "KaTeX_Main-Regular.woff2"})
    std::ofstream(p) << "x";
  fs::create_symlink("/etc/hostname", page / "link.js");

  const std::map<std::string, std::string> routes = rtdr::view_asset_routes({page.string(), katex.string()});
  std::set<std::string> paths;
  for (const auto& [url, file] : routes) paths.insert(url);
  CHECK(paths == std::set<std::string>{"/", "/index.html", "/view.js", "/katex/katex.min.js", "/katex/katex.min.css",
                                       "/katex/fonts/KaTeX_Main-Regular.woff2"});
  CHECK(routes.at("/") == (page / "index.html").string());

  fs::remove(katex / "katex.min.js");
  CHECK_THROWS_WITH(rtdr::view_asset_routes({page.string(), katex.string()}), Catch::Contains("KaTeX is missing"));
  fs::remove(page / "index.html");
  CHECK_THROWS_WITH(rtdr::view_asset_routes({page.string(), katex.string()}), Catch::Contains("no index.html"));
}

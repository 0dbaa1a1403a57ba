// The HTTP server of `rtdr view` (docs/view.md), on cpp-httplib: bound to 127.0.0.1 only, it serves the page's own
// files (app/view/), KaTeX's (Debian's libjs-katex) and what app/view_sequence.h computed, and nothing else.
// No URL is ever turned into a file path: the files it serves are listed when it starts, and a request either
// names one of them or an /api/ route exactly, or gets 404. A target with ".." in any encoding, a backslash, an
// empty segment ("//") or anything but a path ("http://...", "*") is refused with 403 before any route is tried.
#pragma once

#include "app/view_sequence.h"

#include <functional>
#include <map>
#include <string>

namespace rtdr {

// Where the page's files and KaTeX's are: app/view/ of the source tree and libjs-katex's folder, as CMake found
// them (RTDR_VIEW_ASSETS_DIR, RTDR_KATEX_DIR).
struct ViewAssetDirs {
  std::string page;
  std::string katex;
};
ViewAssetDirs default_view_asset_dirs();

// The URL path of every file the server serves, and the file: "/" and "/<name>" for each regular file of the page's
// folder (not its subfolders, no symlinks), "/katex/katex.min.js", "/katex/katex.min.css" and
// "/katex/fonts/<name>" for KaTeX's fonts (which Debian installs as symlinks into /usr/share/fonts: KaTeX's folder
// is the system's, not a user's). Throws rtdr::Error when the page's index.html or KaTeX's files are missing.
std::map<std::string, std::string> view_asset_routes(const ViewAssetDirs& dirs);

// Whether a request may be routed: `target` is the request line's target as sent, `path` its path percent-decoded
// once. False for a target that is not an absolute path, and for a path with "..", a backslash, "//", a NUL, or a
// '%' left after decoding (a second encoding: "%252e%252e").
bool view_request_allowed(const std::string& target, const std::string& path);

// Throws rtdr::Error, as serve_view would, when 127.0.0.1:`port` cannot be listened on (taken by another server):
// run before the filtering, so that a taken port is said at once, not minutes later. Port 0 is always free.
void require_port_free(int port);

// Serves `view` on 127.0.0.1:`port` (0: any free port) until the process is stopped; calls `ready` with the port
// once it listens. Throws rtdr::Error when it cannot listen.
void serve_view(const ViewSequence& view, const std::map<std::string, std::string>& assets, int port,
                const std::function<void(int)>& ready);

}  // namespace rtdr

// The HTTP server of `rtdr view`. See view_server.h; the routes and their answers are in docs/view.md.
#include "app/view_server.h"

#include "core/data_path.h"
#include "core/error.h"
#include "filters/equations.h"

#if RTDR_VIEW
#include <httplib.h>
#endif

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace rtdr {
namespace {

namespace fs = std::filesystem;

#if RTDR_VIEW
// The content type of a served file, by its extension; "" for a file the server does not serve.
std::string content_type(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".png") return "image/png";
  if (ext == ".woff2") return "font/woff2";
  if (ext == ".woff") return "font/woff";
  if (ext == ".ttf") return "font/ttf";
  return "";
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A whole decimal int, or nullopt (absent, empty, a sign where none belongs, trailing text, overflow).
std::optional<int> int_param(const httplib::Request& req, const char* name) {
  if (!req.has_param(name)) return std::nullopt;
  const std::string text = req.get_param_value(name);
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

void send_json(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(body.dump() + "\n", "application/json");
}
void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, status, {{"error", message}});
}

// /api/layer?frame=F&source=S&name=L: the layer's planes as float32, their layout in headers (docs/view.md).
void answer_layer(const ViewSequence& view, const httplib::Request& req, httplib::Response& res) {
  const std::optional<int> frame = int_param(req, "frame");
  const std::optional<LayerSource> source = parse_layer_source(req.get_param_value("source"));
  const std::string name = req.get_param_value("name");
  if (!frame || !source || name.empty())
    return send_error(res, 400, "/api/layer needs frame (a whole number), source (input, golden, port or ref) and name");
  const std::optional<LayerPlanes> planes = view.layer(*source, *frame, name);
  if (!planes)
    return send_error(res, 404, "frame " + std::to_string(*frame) + " has no layer '" + name + "' in " +
                                    req.get_param_value("source"));
  std::string channels;
  for (const std::string& c : planes->channels) channels += (channels.empty() ? "" : ",") + c;
  res.set_header("X-RTDR-Width", std::to_string(planes->width));
  res.set_header("X-RTDR-Height", std::to_string(planes->height));
  res.set_header("X-RTDR-Channels", channels);
  res.set_content(planes->bytes, "application/octet-stream");
}

// /api/probe?frame=F&x=X&y=Y&pass=P&level=L&stream=S: `rtdr probe --json`'s document, byte for byte.
void answer_probe(const ViewSequence& view, const httplib::Request& req, httplib::Response& res) {
  const std::optional<int> frame = int_param(req, "frame"), x = int_param(req, "x"), y = int_param(req, "y");
  const std::optional<int> level = req.has_param("level") ? int_param(req, "level") : std::optional<int>(0);
  const std::string pass = req.get_param_value("pass");
  const std::string stream = req.has_param("stream") ? req.get_param_value("stream") : "direct";
  if (!frame || !x || !y || !level || pass.empty())
    return send_error(res, 400, "/api/probe needs frame, x, y (whole numbers) and pass; level and stream are optional");
  try {
    res.set_content(view.probe_json(*frame, *x, *y, pass, stream, *level), "application/json");
  } catch (const Error& e) {
    send_error(res, 400, e.what());
  }
}

nlohmann::json equations_json() {
  nlohmann::json out = nlohmann::json::object();
  for (const EquationTex& e : equation_tex()) out[std::string(e.key)] = e.tex;
  return out;
}

#endif  // RTDR_VIEW

std::string cannot_listen(int port) {
  return "cannot listen on 127.0.0.1:" + std::to_string(port) + " (in use? --port 0 takes any free port)";
}

// SO_REUSEADDR alone, so that a restarted view gets its port back at once, and a second one does not share it:
// httplib's default adds SO_REUSEPORT, with which two servers listen on one port and split its connections.
void reuse_address_only(int sock) {
  const int yes = 1;
  setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
}

}  // namespace

void require_port_free(int port) {
  if (port == 0) return;
  const int sock = socket(AF_INET, SOCK_STREAM, 0);
  if (sock < 0) throw Error("cannot open a socket: " + std::string(std::strerror(errno)));
  reuse_address_only(sock);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(uint16_t(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool free = bind(sock, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0 && listen(sock, 1) == 0;
  close(sock);
  if (!free) throw Error(cannot_listen(port));
}

bool view_request_allowed(const std::string& target, const std::string& path) {
  if (target.empty() || target[0] != '/' || path.empty() || path[0] != '/') return false;
  for (const char* bad : {"..", "\\", "//", "%"})
    if (path.find(bad) != std::string::npos) return false;
  return path.find('\0') == std::string::npos;
}

#if RTDR_VIEW

ViewAssetDirs default_view_asset_dirs() { return {data_path("view", RTDR_VIEW_ASSETS_DIR), RTDR_KATEX_DIR}; }

std::map<std::string, std::string> view_asset_routes(const ViewAssetDirs& dirs) {
  std::map<std::string, std::string> routes;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dirs.page, ec))
    if (entry.is_regular_file() && !entry.is_symlink() && !content_type(entry.path()).empty())
      routes["/" + entry.path().filename().string()] = entry.path().string();
  if (!routes.count("/index.html"))
    throw Error("the page of rtdr view is missing: no index.html in '" + dirs.page + "'");
  routes["/"] = routes["/index.html"];
  for (const char* file : {"katex.min.js", "katex.min.css"}) {
    const fs::path path = fs::path(dirs.katex) / file;
    if (!fs::is_regular_file(path))
      throw Error("KaTeX is missing: no '" + path.string() + "' (Debian's libjs-katex; tools/setup.sh installs it)");
    routes[std::string("/katex/") + file] = path.string();
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(dirs.katex) / "fonts", ec))
    if (entry.is_regular_file() && !content_type(entry.path()).empty())
      routes["/katex/fonts/" + entry.path().filename().string()] = entry.path().string();
  return routes;
}

void serve_view(const ViewSequence& view, const std::map<std::string, std::string>& assets, int port,
                const std::function<void(int)>& ready) {
  httplib::Server server;
  server.set_socket_options([](socket_t sock) { reuse_address_only(sock); });
  server.set_payload_max_length(4096);  // every route is a GET: no request carries a body worth reading
  server.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    if (view_request_allowed(req.target, req.path)) return httplib::Server::HandlerResponse::Unhandled;
    send_error(res, 403, "refused: rtdr view serves its own files and /api/ routes only");
    return httplib::Server::HandlerResponse::Handled;
  });
  server.Get("/api/info", [&](const httplib::Request&, httplib::Response& res) { send_json(res, 200, view.info()); });
  server.Get("/api/equations",
             [&](const httplib::Request&, httplib::Response& res) { send_json(res, 200, equations_json()); });
  server.Get("/api/layer", [&](const httplib::Request& req, httplib::Response& res) { answer_layer(view, req, res); });
  server.Get("/api/probe", [&](const httplib::Request& req, httplib::Response& res) { answer_probe(view, req, res); });
  server.Get("/api/metrics", [&](const httplib::Request& req, httplib::Response& res) {
    const std::optional<int> frame = int_param(req, "frame");
    const nlohmann::json metrics = frame ? view.metrics(*frame) : nlohmann::json();
    if (metrics.is_null()) return send_error(res, 404, "no metrics: run rtdr view with --ref, and name a viewed frame");
    send_json(res, 200, metrics);
  });
  // The files, by exact path; anything else is 404.
  server.Get(".*", [&](const httplib::Request& req, httplib::Response& res) {
    const auto file = assets.find(req.path);
    if (file == assets.end()) return send_error(res, 404, "no such page: " + req.path);
    res.set_content(read_file(file->second), content_type(file->second));
  });
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    send_error(res, 500, "internal error");
  });

  const int bound = port == 0 ? server.bind_to_any_port("127.0.0.1") : (server.bind_to_port("127.0.0.1", port) ? port : -1);
  if (bound <= 0)
    throw Error(cannot_listen(port));
  ready(bound);
  if (!server.listen_after_bind()) throw Error("the server on 127.0.0.1:" + std::to_string(bound) + " stopped");
}

#else  // Built with -DRTDR_VIEW=OFF (tools/gpu_device.sh): everything but the server.

ViewAssetDirs default_view_asset_dirs() { return {}; }
std::map<std::string, std::string> view_asset_routes(const ViewAssetDirs&) {
  throw Error("this rtdr was built without rtdr view (-DRTDR_VIEW=OFF): install libcpp-httplib-dev and libjs-katex "
              "(tools/setup.sh) and build with -DRTDR_VIEW=ON");
}
void serve_view(const ViewSequence&, const std::map<std::string, std::string>&, int, const std::function<void(int)>&) {
  view_asset_routes({});
}

#endif  // RTDR_VIEW

}  // namespace rtdr

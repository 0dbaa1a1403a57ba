// What `rtdr probe --json` prints, and `rtdr view` answers at /api/probe (docs/view.md): one document, made here
// only, so that a script gets the same bytes from either.
#pragma once

#include "filters/probe.h"

#include <nlohmann/json.hpp>

#include <string>

namespace rtdr {

// The question a probe answers: which method, frame, pixel, pass, stream and level.
struct ProbeQuestion {
  std::string method;
  int frame = 0;
  int x = 0, y = 0;
  std::string pass;
  std::string stream;
  int level = 0;
};

// {"method", "frame", "pixel": [x, y], "pass", "stream", "level", "terms": Probe::json()}.
nlohmann::json probe_document(const ProbeQuestion& question, const Probe& probe);
// The document as `rtdr probe --json` prints it: indented by 2, ending in a newline.
std::string probe_json_text(const ProbeQuestion& question, const Probe& probe);

}  // namespace rtdr

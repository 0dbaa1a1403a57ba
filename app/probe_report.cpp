#include "app/probe_report.h"

namespace rtdr {

nlohmann::json probe_document(const ProbeQuestion& q, const Probe& probe) {
  return {{"method", q.method}, {"frame", q.frame},   {"pixel", {q.x, q.y}},  {"pass", q.pass},
          {"stream", q.stream}, {"level", q.level}, {"terms", probe.json()}};
}

std::string probe_json_text(const ProbeQuestion& question, const Probe& probe) {
  return probe_document(question, probe).dump(2) + "\n";
}

}  // namespace rtdr

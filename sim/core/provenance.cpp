#include "sim/core/provenance.hpp"

#ifndef FORMSIM_VERSION
#define FORMSIM_VERSION "unknown"
#endif

namespace formsim::sim {

std::string Override::Describe() const {
  std::string s = origin + " " + key + "=" + value;
  if (step >= 0) s += " at step " + std::to_string(step);
  return s;
}

Json Provenance::ToJson() const {
  Json j = Json::Object();
  j["formsim_version"] = FormsimVersion();
  j["scenario_file"] = file;
  j["scenario_sha256"] = sha256;
  j["seed"] = static_cast<unsigned long long>(seed);
  Json list = Json::Array();
  for (const Override& o : overrides) {
    Json e = Json::Object();
    e["origin"] = o.origin;
    e["key"] = o.key;
    e["value"] = o.value;
    if (o.step >= 0) e["step"] = static_cast<long long>(o.step);
    list.Push(e);
  }
  j["overrides"] = list;
  return j;
}

std::string FormsimVersion() { return FORMSIM_VERSION; }

}  // namespace formsim::sim

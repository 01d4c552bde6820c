// libFuzzer harness for session files as `formsim replay FILE` reads them: any bytes parsed by
// SessionRecord::Parse (the YAML limits, the strict record reader, the scenario texts checked
// against their SHA-256) and, when they parse, replayed through SessionReplay as `replay` does
// (the history bound, no CSV, no pictures) for a bounded number of steps. A refusal is the
// expected outcome for most inputs; a crash, an abort, a sanitizer report or a hang is a bug.
// Seeds: tests/fuzz/session_seeds (sessions written by `formsim gui --session`).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "sim/core/run_output.hpp"
#include "sim/session/session_record.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace formsim::sim;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    SessionRecord record = SessionRecord::Parse(text, "fuzz.session.yaml");
    (void)record.ToYaml(record.end_step() < 0 ? 0 : record.end_step());
    SessionReplay replay(std::move(record), [](Experiment& e) {
      e.mutable_recorder().SetHistoryLimit(kRunHistoryRows);
    });
    // A recorded end may lie 10^8 steps ahead: a few hundred steps show whether the events fit.
    for (int k = 0; k < 400 && replay.Advance(); ++k) {
    }
    (void)replay.session().exp().Summary().Dump();
  } catch (const std::exception&) {
    // Refused with a message: fine.
  }
  return 0;
}

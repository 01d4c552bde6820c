#pragma once
/// \file Numbers as text, one way for every output: the CSV, summary.json, saved scenarios and
/// the GUI's edits all write a double as the shortest text that reads back to the same bits
/// (`0.03`, never `0.029999999999999999`), and non-finite values as `nan`, `inf`, `-inf`.

#include <cstdint>
#include <string>

namespace formsim::sim {

/// Shortest round-trip text of `v` ("0.03", "1e-09", "12345678901"); "nan", "inf" or "-inf"
/// when not finite.
std::string FormatDouble(double v);
/// Appends FormatDouble(v) to `out` without allocating a temporary (hot CSV path).
void AppendDouble(std::string& out, double v);

/// printf-style text for labels and notes ("%.1f m"); never for data (use FormatDouble).
std::string Sprintf(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
/// The same text appended to `out` (no temporary: allocates only when `out` must grow).
void AppendSprintf(std::string& out, const char* fmt, ...) __attribute__((format(printf, 2, 3)));

/// Parses the whole of `text` as a finite double. Returns false on anything else (empty, junk
/// after the number, out of range, nan, inf).
bool ParseFiniteDouble(const std::string& text, double* out);
/// Parses the whole of `text` as a base-10 integer in [lo, hi]. Returns false otherwise
/// (including "1e3", "1.0" and values that do not fit).
bool ParseInteger(const std::string& text, long long lo, long long hi, long long* out);
/// Parses an unsigned 64-bit integer (seeds): digits only, no sign, must fit.
bool ParseUint64(const std::string& text, std::uint64_t* out);

}  // namespace formsim::sim

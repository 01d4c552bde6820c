#pragma once
/// \file Numbers as text: the one formatter of every layer (control's messages, sim's CSV,
/// summary.json and saved scenarios, app's labels, figures and tables). Data is written as the
/// shortest text that reads back to the same bits (`0.03`, never `0.029999999999999999`);
/// labels choose significant digits, fixed decimals or a clock. sim code names these `sim::`
/// (sim/core/number_format.hpp).

#include <cstdint>
#include <cstdio>
#include <string>

namespace formsim::control {

/// Shortest round-trip text of `v` ("0.03", "1e-09", "12345678901"); "nan", "inf" or "-inf"
/// when not finite. The only form for data.
std::string FormatDouble(double v);
/// Appends FormatDouble(v) to `out` without allocating a temporary (hot CSV path).
void AppendDouble(std::string& out, double v);

/// `digits` significant digits, printf's %g ("0.3", "1.5e-05", "120"): labels, messages and
/// table cells where the reader wants a few digits. "nan", "inf", "-inf" when not finite.
std::string FormatSignificant(double v, int digits = 6);
/// `decimals` digits after the point ("0.250"). A value that would print as minus zero prints
/// as zero. With `trim`, trailing zeros and a bare point go ("0.25", "3"): SVG coordinates.
std::string FormatFixed(double v, int decimals, bool trim = false);
/// `digits` significant digits times a power of ten, written the way tables in papers do
/// ("7.2e-2", "-1.30e3"); "0" for zero, %g's text when not finite.
std::string FormatScientific(double v, int digits);
/// A table cell: `digits` significant digits with trailing zeros kept, so a column's numbers
/// line up and read alike ("0.007120", "12.50"); scientific in the papers' style below 1e-4 and
/// from 1e6 on ("7.120e-5"); a whole number below 1e6 as an integer ("3", a count); "0" for
/// zero; "nan", "inf", "-inf" when not finite.
std::string FormatCell(double v, int digits);
/// mean ± σ for a table cell: the mean as FormatCell gives it and σ written to the same decimal
/// place ("0.007559 ± 0.000680", "(7.559 ± 0.680)e-5"); the mean alone when σ is not finite.
std::string FormatMeanSigma(double mean, double sigma, int digits);
/// A whole number as an integer ("15", "-3"), anything else as FormatDouble: ranges and
/// defaults in help texts.
std::string FormatWholeOrShortest(double v);
/// A duration in seconds as a clock, "m:ss" or "h:mm:ss" (negative and non-finite as 0:00):
/// progress bars and time left.
std::string FormatClock(double seconds);

/// printf-style text for labels and notes ("%.1f m"); never for data (use FormatDouble).
std::string Sprintf(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
/// The same text appended to `out` (no temporary: allocates only when `out` must grow).
void AppendSprintf(std::string& out, const char* fmt, ...) __attribute__((format(printf, 2, 3)));

/// printf-style text written to `out` (stdout, stderr): the CLI's messages and reports. The one
/// place outside this module's files where text reaches a stream with numbers in it.
void Print(std::FILE* out, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
/// Simulated time as people read it on screen: "t = 12.34 s" (two decimals).
std::string FormatSimTime(double t);

/// Parses the whole of `text` as a finite double. Returns false on anything else (empty, junk
/// after the number, out of range, nan, inf).
bool ParseFiniteDouble(const std::string& text, double* out);
/// Parses the whole of `text` as a base-10 integer in [lo, hi]. Returns false otherwise
/// (including "1e3", "1.0" and values that do not fit).
bool ParseInteger(const std::string& text, long long lo, long long hi, long long* out);
/// Parses an unsigned 64-bit integer (seeds): digits only, no sign, must fit.
bool ParseUint64(const std::string& text, std::uint64_t* out);

}  // namespace formsim::control

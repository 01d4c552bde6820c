#pragma once
/// \file The number formatter (control/common/number_format.hpp), named in sim's namespace so
/// that sim and app code write `sim::FormatDouble`. There is no second implementation.

#include "control/common/number_format.hpp"

namespace formsim::sim {

using control::AppendDouble;
using control::AppendSprintf;
using control::FormatCell;
using control::FormatClock;
using control::FormatDouble;
using control::FormatFixed;
using control::FormatMeanSigma;
using control::FormatScientific;
using control::FormatSignificant;
using control::FormatWholeOrShortest;
using control::ParseFiniteDouble;
using control::ParseInteger;
using control::ParseUint64;
using control::Print;
using control::FormatSimTime;
using control::Sprintf;

}  // namespace formsim::sim

#pragma once
// Numbers in CSV cells rounded to what they mean: one rule per unit, so that a spreadsheet
// shows 30.0 mm rather than 30.000000000000004 and two runs compare as text. The JSON
// reports keep full precision; only the CSV writers use this.
#include <string>

namespace palpa::report {

/// What a CSV number measures; each kind has one number of decimals.
enum class CsvUnit {
  Millimetre,  ///< lengths in mm: 0.1 mm
  Newton,      ///< forces in N: 0.01 N
  Second,      ///< times in s: 0.01 s (the xAPI duration's resolution)
  Fraction,    ///< shares 0..1 (score, sensitivity, coverage): 0.001
  Ratio,       ///< dimensionless ratios (palpate/search force): 0.01
  Score100,    ///< the score out of 100: 0.1
  Cusum,       ///< CUSUM chart values: 0.01
};

/// Decimals written for the unit (1 for Millimetre, 2 for Newton, ...).
int csv_decimals(CsvUnit unit);

/// The value with exactly csv_decimals(unit) decimals, rounded to nearest from its exact
/// binary value; "0.0", never "-0.0", for a negative value that rounds to zero; empty for
/// NaN and infinities (an empty cell: "not measured").
std::string csv_number(double value, CsvUnit unit);

}  // namespace palpa::report

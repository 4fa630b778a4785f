// What the photometric-file readers share (ies_reader.cpp, eulumdat_reader.cpp, with the
// helpers defined in photometry.cpp): the plausibility limits, text helpers, the range
// checks on numbers, and the stored candela web with its symmetry expansion and the
// checks once it is in place. Not part of core's interface.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/light/photometry.h"

namespace ilp::photometry_detail {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDegToRad = kPi / 180.0;
inline constexpr double kFeetToMetres = 0.3048;
// Angles closer than this (degrees) are the same angle (files print 2-6 decimals).
inline constexpr double kAngleTolDeg = 1e-6;
// Plausibility limits: beyond them a value is a corrupt file, not a luminaire.
// A text field or keyword (luminaire, manufacturer, catalogue): at most this long
// (LM-63 lines are at most 256 characters, EULUMDAT's 78).
inline constexpr std::size_t kMaxTextChars = 256;
inline constexpr double kMaxCandela = 1e9;       // the brightest searchlights are ~1e9 cd
// A non-zero intensity below this is no measurement (a subnormal such as 4e-320 once
// made the flux underflow and the direct light NaN, far from the file): refused.
// Round-off of a computed web (1000 cos 90° = 6e-14) stays well above it.
inline constexpr double kMinNonZeroCandela = 1e-30;
inline constexpr double kMaxFluxLm = 1e8;        // a 1 MW sodium lamp makes ~1.5e8 lm
inline constexpr double kMaxPowerW = 1e7;
inline constexpr double kMaxDimensionM = 1000.0;
inline constexpr double kMaxDimensionMm = 1e6;
inline constexpr double kMaxFactor = 1e6;        // candela multiplier, EULUMDAT conversion factor
inline constexpr long kMaxCount = 10000000;     // angle counts; checked against the file's size anyway
inline constexpr std::size_t kMaxFileBytes = std::size_t{64} << 20;
// Header-vs-data checks warn beyond this many percentage points.
inline constexpr double kHeaderCheckPoints = 2.0;

// Throws PhotometryError "PATH:LINE: field FIELD: WHAT".
[[noreturn]] void fail(const std::string& path, int line, const std::string& field, const std::string& what);

// x with 6 significant digits, for messages.
std::string fmt(double x);
// ASCII letters upper-cased.
std::string upper(std::string_view s);
// Without leading and trailing white space.
std::string_view trim(std::string_view s);
// Text fields as UTF-8: kept if they already are, else read as ISO-8859-1 (EULUMDAT's charset).
std::string to_utf8(std::string_view s);

// A text field as kept: at most kMaxTextChars (else fail at path:line naming `field`),
// UTF-8, control characters escaped (\xNN: a vendor's escape codes are shown, never
// obeyed by a terminal).
std::string bounded_text(std::string_view s, const std::string& path, int line, const std::string& field);
// The text without a UTF-8 BOM and without anything from a DOS end-of-file byte (^Z) on.
std::string_view strip_bom_and_eof(std::string_view text);
// Lines split at LF, CRLF or a lone CR; line i of the result is file line i + 1.
std::vector<std::string_view> split_lines(std::string_view text);
// A finite number written in full (leading '+' allowed; `decimal_comma`: "0,5" = 0.5).
bool parse_number(std::string_view token, double& out, bool decimal_comma = false);

inline bool is_integer(double x) { return std::abs(x - std::round(x)) < 1e-9; }
// The same angle to within kAngleTolDeg.
inline bool near(double a, double b) { return std::abs(a - b) <= kAngleTolDeg; }

// A field name, built only when a message needs it (a string, or a callable returning one).
template <class Name>
std::string name_of(const Name& name) {
  if constexpr (std::is_invocable_v<const Name&>) {
    return name();
  } else {
    return std::string(name);
  }
}

// The range checks both readers share, on a Reader with line(), number(field) and
// path(): a number within [lo, hi], a whole number within [lo, hi].
template <class Reader>
class BoundedNumbers {
 public:
  template <class Name>
  double number_in(const Name& field, double lo, double hi) {
    Reader& r = static_cast<Reader&>(*this);
    const int at = r.line();
    const double v = r.number(field);
    if (v < lo || v > hi) fail(r.path(), at, name_of(field), fmt(v) + " is outside [" + fmt(lo) + ", " + fmt(hi) + "]");
    return v;
  }
  template <class Name>
  long integer_in(const Name& field, long lo, long hi) {
    Reader& r = static_cast<Reader&>(*this);
    const int at = r.line();
    const double v = r.number(field);
    if (!is_integer(v)) fail(r.path(), at, name_of(field), fmt(v) + " is not a whole number");
    if (v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
      fail(r.path(), at, name_of(field),
           fmt(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    return std::lround(v);
  }
};

// The candela planes as the file stores them, before the symmetry expansion.
struct StoredWeb {
  std::vector<double> c_deg;  // the file's planes, in file order (any of them may be >= 360 before wrap)
  Eigen::MatrixXd cd;         // #planes by #gamma
  int plane_360 = -1;         // index of a stored C = 360 plane (IES 0..360), else -1
};

// Fills p.c_angles_deg and p.candela_cd from the stored planes and p.symmetry.
void expand_web(Photometry& p, const StoredWeb& w);
// Common checks once the web is in place: something is emitted, flux and upward share.
void finish(Photometry& p, int data_line);
// Adds "PATH: MESSAGE" to p.warnings.
void warn(Photometry& p, const std::string& message);

}  // namespace ilp::photometry_detail

// Text of the HTML report (src/cli/report.cpp and its sections): escaping
// and numbers as people read them (grouped digits, a real minus sign,
// percentages with powers of ten), in UTF-8.
#pragma once

#include <cstdint>
#include <string>

namespace bodt_cli {

extern const char* const kDeg;   // degree sign
extern const char* const kDash;  // en dash

std::string escape_html(const std::string& s);
// printf of one double.
std::string format(const char* fmt, double v);
// `decimals` after the point; -0.00 shows as 0.00.
std::string fixed(double v, int decimals);
// Full precision, for data-value attributes (round-trips a double).
std::string exact(double v);
// 1234567 -> "1,234,567".
std::string grouped(int64_t v);
// A real number with a proper minus sign (U+2212), `digits` significant.
std::string general(double v, int digits = 6);
// `s` with a leading '-' made U+2212.
std::string with_minus(std::string s);
// A signed percentage: "+1.25 %", or "-1.1 x 10^-13 %" (typeset) when tiny.
std::string percent(double p);

}  // namespace bodt_cli

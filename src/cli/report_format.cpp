#include "cli/report_format.hpp"

#include <cmath>
#include <cstdio>

namespace bodt_cli {

const char* const kDeg = "\xC2\xB0";
const char* const kDash = "\xE2\x80\x93";

std::string escape_html(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string format(const char* fmt, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    std::string s = buf;
    if (s == "-0" || s.rfind("-0.", 0) == 0) {  // -0.00 reads as 0.00
        bool all_zero = s.find_first_not_of("-0.") == std::string::npos;
        if (all_zero) s.erase(0, 1);
    }
    return s;
}

std::string exact(double v) { return format("%.17g", v); }

std::string grouped(int64_t v) {
    std::string digits = std::to_string(v < 0 ? -v : v);
    std::string out;
    const size_t n = digits.size();
    for (size_t i = 0; i < n; ++i) {
        if (i > 0 && (n - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return v < 0 ? "\xE2\x88\x92" + out : out;  // U+2212 minus
}

std::string general(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    std::string s = buf;
    if (!s.empty() && s[0] == '-') s = "\xE2\x88\x92" + s.substr(1);
    return s;
}

std::string with_minus(std::string s) {
    if (!s.empty() && s[0] == '-') s = "\xE2\x88\x92" + s.substr(1);
    return s;
}

// A signed percentage: "+1.25 %", or "−1.1 × 10⁻¹³ %" when tiny.
std::string percent(double p) {
    const char* sign = p < 0 ? "\xE2\x88\x92" : "+";
    const double a = std::fabs(p);
    if (a == 0.0) return "0\xE2\x80\x89%";
    if (a >= 0.01) return sign + fixed(a, 2) + "\xE2\x80\x89%";
    static const char* const sup[10] = {"\xE2\x81\xB0", "\xC2\xB9", "\xC2\xB2", "\xC2\xB3",
                                        "\xE2\x81\xB4", "\xE2\x81\xB5", "\xE2\x81\xB6",
                                        "\xE2\x81\xB7", "\xE2\x81\xB8", "\xE2\x81\xB9"};
    int e = static_cast<int>(std::floor(std::log10(a)));
    double m = a / std::pow(10.0, e);
    if (m >= 9.95) {  // 9.96e-14 prints as 10.0
        m /= 10.0;
        ++e;
    }
    std::string exp_text = e < 0 ? "\xE2\x81\xBB" : "";  // superscript minus
    for (char digit : std::to_string(e < 0 ? -e : e)) exp_text += sup[digit - '0'];
    return sign + fixed(m, 1) + "\xE2\x80\x89\xC3\x97\xE2\x80\x89" "10" + exp_text +
           "\xE2\x80\x89%";
}

}  // namespace bodt_cli

#include "io/text_scanner.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace bodt {

std::string read_file_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(BODT_ERR_IO, "cannot open '" + path + "': " + std::strerror(errno));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw Error(BODT_ERR_IO, "cannot read '" + path + "'");
    return buffer.str();
}

TextScanner::TextScanner(const std::string& path) : path_(path), text_(read_file_text(path)) {}

void TextScanner::fail(const std::string& message) const {
    throw Error(BODT_ERR_IO, path_ + ":" + std::to_string(line_) + ": " + message);
}

bool TextScanner::next(std::string_view& token) {
    while (pos_ < text_.size()) {
        const char c = text_[pos_];
        if (c == '\n') {
            ++line_;
            ++pos_;
        } else if (c == '#') {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            ++pos_;
        } else {
            break;
        }
    }
    if (pos_ >= text_.size()) return false;
    const size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])) && text_[pos_] != '#') ++pos_;
    token = std::string_view(text_).substr(start, pos_ - start);
    return true;
}

std::string_view TextScanner::expect(const char* what) {
    std::string_view token;
    if (!next(token)) fail(std::string("unexpected end of file while reading ") + what);
    return token;
}

int64_t TextScanner::read_int(const char* what) {
    const std::string_view token = expect(what);
    int64_t value = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size())
        fail(std::string("expected an integer for ") + what + ", found '" + std::string(token) + "'");
    return value;
}

double TextScanner::read_double(const char* what) {
    const std::string_view token = expect(what);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size())
        fail(std::string("expected a number for ") + what + ", found '" + std::string(token) + "'");
    if (!std::isfinite(value)) fail(std::string(what) + " is not finite ('" + std::string(token) + "')");
    return value;
}

int64_t TextScanner::read_count(const char* what, int64_t min_bytes_each) {
    const int64_t n = read_int(what);
    if (n < 0) fail(std::string(what) + " is negative (" + std::to_string(n) + ")");
    const int64_t room = static_cast<int64_t>(text_.size() - pos_);
    if (n > room / std::max<int64_t>(min_bytes_each, 1))
        fail(std::string(what) + " " + std::to_string(n) + " is more than the rest of the file can hold");
    return n;
}

}  // namespace bodt

// A whitespace-separated token reader over a whole text file, with '#'
// comments, line numbers for messages, and checked number parsing.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace bodt {

// The whole file, as bytes; Error(BODT_ERR_IO) if it cannot be opened or read.
std::string read_file_text(const std::string& path);

class TextScanner {
public:
    // Reads the file; throws Error(BODT_ERR_IO) if it cannot.
    explicit TextScanner(const std::string& path);

    // Next token, or false at the end of the file.
    bool next(std::string_view& token);
    // Next token; throws "unexpected end of file while reading <what>".
    std::string_view expect(const char* what);

    int64_t read_int(const char* what);
    double read_double(const char* what);  // finite values only
    // A count read from the file, checked to be >= 0 and small enough for
    // the remaining bytes to hold `min_bytes_each` bytes per item.
    int64_t read_count(const char* what, int64_t min_bytes_each);

    [[noreturn]] void fail(const std::string& message) const;
    const std::string& path() const { return path_; }
    int64_t line() const { return line_; }

private:
    std::string path_;
    std::string text_;
    size_t pos_ = 0;
    int64_t line_ = 1;
};

}  // namespace bodt

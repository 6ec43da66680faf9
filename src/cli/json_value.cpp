#include "cli/json_value.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace bodt_cli {

const JsonValue* JsonValue::get(const char* key) const {
    const JsonValue* found = nullptr;
    if (type == Type::Object)
        for (const auto& m : members)
            if (m.first == key) found = &m.second;
    return found;
}

namespace {

class Parser {
public:
    explicit Parser(const std::string& text) : s_(text) {}

    bool document(JsonValue& out, std::string& error) {
        if (!value(out, 0)) {
            error = where() + ": " + error_;
            return false;
        }
        space();
        if (pos_ != s_.size()) {
            error = where() + ": unexpected text after the JSON value";
            return false;
        }
        return true;
    }

private:
    static constexpr int kMaxDepth = 64;

    std::string where() const {
        size_t line = 1, column = 1;
        for (size_t k = 0; k < pos_ && k < s_.size(); ++k) {
            if (s_[k] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        return "line " + std::to_string(line) + ", column " + std::to_string(column);
    }

    bool fail(const std::string& message) {
        error_ = message;
        return false;
    }

    void space() {
        while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r'))
            ++pos_;
    }

    // Moves past `c` when it comes next; whether it did.
    bool skip(char c) {
        if (pos_ >= s_.size() || s_[pos_] != c) return false;
        ++pos_;
        return true;
    }

    bool literal(const char* word) {
        size_t n = 0;
        while (word[n]) ++n;
        if (s_.compare(pos_, n, word) != 0) return fail(std::string("expected ") + word);
        pos_ += n;
        return true;
    }

    bool value(JsonValue& v, int depth) {
        if (depth > kMaxDepth) return fail("nested too deeply");
        space();
        if (pos_ >= s_.size()) return fail("unexpected end of the text");
        const char c = s_[pos_];
        if (c == '{') return object(v, depth);
        if (c == '[') return array(v, depth);
        if (c == '"') {
            v.type = JsonValue::Type::String;
            return string(v.text);
        }
        if (c == 't' || c == 'f') {
            v.type = JsonValue::Type::Bool;
            v.boolean = c == 't';
            return literal(c == 't' ? "true" : "false");
        }
        if (c == 'n') {
            v.type = JsonValue::Type::Null;
            return literal("null");
        }
        return number(v);
    }

    bool object(JsonValue& v, int depth) {
        v.type = JsonValue::Type::Object;
        return elements('}', [&] {
            space();
            if (pos_ >= s_.size() || s_[pos_] != '"') return fail("expected a member name in quotes");
            std::string key;
            if (!string(key)) return false;
            space();
            if (!skip(':')) return fail("expected ':'");
            v.members.emplace_back(std::move(key), JsonValue());
            return value(v.members.back().second, depth + 1);
        });
    }

    bool array(JsonValue& v, int depth) {
        v.type = JsonValue::Type::Array;
        return elements(']', [&] {
            v.items.emplace_back();
            return value(v.items.back(), depth + 1);
        });
    }

    // The elements of an object or array, from its opening bracket to
    // `close`: none, or element() for each, separated by commas.
    template <class Element>
    bool elements(char close, Element element) {
        ++pos_;
        space();
        if (skip(close)) return true;
        while (true) {
            if (!element()) return false;
            space();
            if (skip(',')) continue;
            if (skip(close)) return true;
            return fail(std::string("expected ',' or '") + close + "'");
        }
    }

    bool hex4(unsigned& code) {
        if (pos_ + 4 > s_.size()) return fail("a \\u escape needs four hex digits");
        code = 0;
        for (int k = 0; k < 4; ++k) {
            const char h = s_[pos_++];
            code <<= 4;
            if (h >= '0' && h <= '9') code |= static_cast<unsigned>(h - '0');
            else if (h >= 'a' && h <= 'f') code |= static_cast<unsigned>(h - 'a' + 10);
            else if (h >= 'A' && h <= 'F') code |= static_cast<unsigned>(h - 'A' + 10);
            else return fail("a \\u escape needs four hex digits");
        }
        return true;
    }

    static void utf8(unsigned code, std::string& out) {
        if (code < 0x80) {
            out += static_cast<char>(code);
        } else if (code < 0x800) {
            out += static_cast<char>(0xC0 | (code >> 6));
            out += static_cast<char>(0x80 | (code & 0x3F));
        } else if (code < 0x10000) {
            out += static_cast<char>(0xE0 | (code >> 12));
            out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (code & 0x3F));
        } else {
            out += static_cast<char>(0xF0 | (code >> 18));
            out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
            out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (code & 0x3F));
        }
    }

    bool string(std::string& out) {
        ++pos_;  // the opening quote
        out.clear();
        while (pos_ < s_.size()) {
            const char c = s_[pos_++];
            if (c == '"') return true;
            if (static_cast<unsigned char>(c) < 0x20) return fail("a control character inside a string");
            if (c != '\\') {
                out += c;
                continue;
            }
            if (pos_ >= s_.size()) break;
            const char e = s_[pos_++];
            switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case '/': out += '/'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'u': {
                    unsigned code = 0;
                    if (!hex4(code)) return false;
                    if (code >= 0xD800 && code < 0xDC00) {  // a surrogate pair
                        unsigned low = 0;
                        if (s_.compare(pos_, 2, "\\u") != 0) return fail("a lone UTF-16 surrogate");
                        pos_ += 2;
                        if (!hex4(low)) return false;
                        if (low < 0xDC00 || low >= 0xE000) return fail("a lone UTF-16 surrogate");
                        code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
                    } else if (code >= 0xDC00 && code < 0xE000) {
                        return fail("a lone UTF-16 surrogate");
                    }
                    utf8(code, out);
                    break;
                }
                default: return fail(std::string("unknown escape \\") + e);
            }
        }
        return fail("a string is not closed");
    }

    bool number(JsonValue& v) {
        const size_t start = pos_;
        const auto digits = [&] {
            const size_t from = pos_;
            while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') ++pos_;
            return pos_ > from;
        };
        skip('-');
        if (!skip('0') && !digits()) return fail("expected a value");
        if (skip('.') && !digits()) return fail("expected digits after '.'");
        if (skip('e') || skip('E')) {
            if (!skip('+')) skip('-');
            if (!digits()) return fail("expected digits in the exponent");
        }
        v.type = JsonValue::Type::Number;
        v.text = s_.substr(start, pos_ - start);
        errno = 0;
        v.number = std::strtod(v.text.c_str(), nullptr);
        if (errno == ERANGE && !std::isfinite(v.number)) return fail("a number out of range");
        return true;
    }

    const std::string& s_;
    size_t pos_ = 0;
    std::string error_;
};

}  // namespace

bool parse_json(const std::string& text, JsonValue& out, std::string& error) {
    out = JsonValue();
    return Parser(text).document(out, error);
}

}  // namespace bodt_cli

// A small JSON reader (RFC 8259) for what the command reads back of its own
// output: `bodt report --run RUN.json` takes the object of `bodt improve
// --json`.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace bodt_cli {

struct JsonValue {
    enum class Type { Null, Bool, Number, String, Array, Object };
    Type type = Type::Null;
    bool boolean = false;
    double number = 0.0;
    std::string text;  // a string's value, or a number as written
    std::vector<JsonValue> items;
    std::vector<std::pair<std::string, JsonValue>> members;

    // The member `key` of an object (the last one of that name), or nullptr.
    const JsonValue* get(const char* key) const;
    bool is_number() const { return type == Type::Number; }
    bool is_string() const { return type == Type::String; }
};

// Parses the whole of `text` (one value, white space around it).  False with
// `error` ("line 3, column 7: expected ':'") otherwise.  Nesting deeper than
// 64 levels is refused.
bool parse_json(const std::string& text, JsonValue& out, std::string& error);

}  // namespace bodt_cli

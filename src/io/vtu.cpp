// VTK XML UnstructuredGrid (.vtu): see vtu.hpp for what is written and read.
//
// The reader parses the whole file with a small XML tokenizer (elements,
// attributes, text, comments, CDATA; entity references decoded; no DOCTYPE;
// raw appended data kept as bytes) into a flat element tree, then reads the
// few arrays it needs (their binary data: vtu_binary.cpp).  Nothing is
// allocated from a count in the file: arrays are decoded from the data
// actually present and only then compared with NumberOfPoints / Cells.
#include "io/vtu.hpp"

#include "io/byte_order.hpp"
#include "io/output_file.hpp"
#include "io/text_scanner.hpp"
#include "io/vtk_cells.hpp"
#include "io/vtu_binary.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string_view>
#include <utility>
#include <vector>

namespace bodt {

namespace {

// ------------------------------------------------------------------ XML

struct XmlElement {
    std::string name;
    std::vector<std::pair<std::string, std::string>> attrs;
    std::vector<size_t> children;
    size_t offset = 0;  // of the '<' of the start tag
    // Character data: ranges of the file (begin, end, is CDATA).
    struct Range {
        size_t begin, end;
        bool cdata;
    };
    std::vector<Range> text;
    // Raw appended data (<AppendedData encoding="raw">): the bytes after
    // its '_', [raw_begin, raw_end) of the file, never parsed as XML; an
    // empty range for a self-closing one.
    size_t raw_begin = 0, raw_end = 0;

    const std::string* attr(const char* key) const {
        for (const auto& [k, v] : attrs)
            if (k == key) return &v;
        return nullptr;
    }
};

class XmlDocument {
public:
    XmlDocument(std::string path, std::string text) : path_(std::move(path)), buf_(std::move(text)) { parse(); }

    const std::string& path() const { return path_; }
    const std::string& buffer() const { return buf_; }
    const XmlElement& root() const { return elems_[0]; }
    const XmlElement& element(size_t i) const { return elems_[i]; }

    int64_t line_at(size_t offset) const {
        offset = std::min(offset, buf_.size());
        return 1 + std::count(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
    }
    [[noreturn]] void fail_at(size_t offset, const std::string& message) const {
        throw Error(BODT_ERR_IO, path_ + ":" + std::to_string(line_at(offset)) + ": " + message);
    }
    [[noreturn]] void fail(const XmlElement& e, const std::string& message) const { fail_at(e.offset, message); }
    [[noreturn]] void fail_line(int64_t line, const std::string& message) const {
        throw Error(BODT_ERR_IO, path_ + ":" + std::to_string(line) + ": " + message);
    }

    // Decodes entity references in buf_[begin, end) (no CDATA) onto out.
    void decode_entities(size_t begin, size_t end, std::string& out) const {
        for (size_t p = begin; p < end;) {
            const char c = buf_[p];
            if (c != '&') {
                out.push_back(c);
                ++p;
                continue;
            }
            const size_t semi = buf_.find(';', p);
            if (semi == std::string::npos || semi >= end || semi - p > 12)
                fail_at(p, "unterminated entity reference");
            const std::string_view ent(buf_.data() + p + 1, semi - p - 1);
            if (ent == "lt") out.push_back('<');
            else if (ent == "gt") out.push_back('>');
            else if (ent == "amp") out.push_back('&');
            else if (ent == "quot") out.push_back('"');
            else if (ent == "apos") out.push_back('\'');
            else if (ent.size() >= 2 && ent[0] == '#') {
                const bool hex = ent[1] == 'x';
                uint32_t cp = 0;
                const char* first = ent.data() + (hex ? 2 : 1);
                const auto [ptr, ec] = std::from_chars(first, ent.data() + ent.size(), cp, hex ? 16 : 10);
                if (ec != std::errc() || ptr != ent.data() + ent.size() || first == ptr || cp == 0 || cp > 0x10FFFF)
                    fail_at(p, "invalid character reference '&" + std::string(ent) + ";'");
                append_utf8(cp, out);
            } else {
                fail_at(p, "unknown entity '&" + std::string(ent) + ";'");
            }
            p = semi + 1;
        }
    }

private:
    static void append_utf8(uint32_t cp, std::string& out) {
        if (cp < 0x80) {
            out.push_back(static_cast<char>(cp));
        } else if (cp < 0x800) {
            out.push_back(static_cast<char>(0xC0 | (cp >> 6)));
            out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
        } else if (cp < 0x10000) {
            out.push_back(static_cast<char>(0xE0 | (cp >> 12)));
            out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
        } else {
            out.push_back(static_cast<char>(0xF0 | (cp >> 18)));
            out.push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
            out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
            out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
        }
    }

    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
    static bool is_name_start(char c) {
        return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || c == ':' ||
               static_cast<unsigned char>(c) >= 0x80;
    }
    static bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }

    bool starts(size_t p, const char* s) const { return buf_.compare(p, std::strlen(s), s) == 0; }
    void skip_space(size_t& p) const {
        while (p < buf_.size() && is_space(buf_[p])) ++p;
    }
    std::string read_name(size_t& p, const char* what) const {
        if (p >= buf_.size()) fail_at(p, std::string("unexpected end of file in ") + what);
        if (!is_name_start(buf_[p])) fail_at(p, std::string("malformed ") + what);
        const size_t start = p;
        while (p < buf_.size() && is_name_char(buf_[p])) ++p;
        return buf_.substr(start, p - start);
    }
    // Skips to just past `end`, which must come before the end of the file.
    void skip_past(size_t& p, const char* end, const char* what) const {
        const size_t q = buf_.find(end, p);
        if (q == std::string::npos) fail_at(p, std::string("unexpected end of file: unterminated ") + what);
        p = q + std::strlen(end);
    }

    // Raw appended data may hold any byte, '<' too, so it is not parsed: it
    // starts after a '_' (after optional whitespace) and ends at the last
    // </AppendedData> of the file, where VTK and meshio end it.  Without an
    // encoding attribute appended data is raw, as in VTK.
    void skip_raw_data(XmlElement& e, size_t& p) const {
        const std::string* encoding = e.attr("encoding");
        if (encoding && *encoding != "raw") return;
        size_t q = p;
        skip_space(q);
        if (q >= buf_.size() || buf_[q] != '_') fail_at(q, "raw appended data must start with '_'");
        const size_t end = buf_.rfind("</AppendedData>");
        if (end == std::string::npos || end <= q)
            fail_at(e.offset, "unexpected end of file: raw <AppendedData> without </AppendedData>");
        e.raw_begin = q + 1;
        e.raw_end = end;
        p = end;
    }

    void parse() {
        size_t p = 0;
        if (starts(0, "\xEF\xBB\xBF")) p = 3;  // UTF-8 byte order mark
        std::vector<size_t> open;
        bool have_root = false;
        while (p < buf_.size()) {
            if (buf_[p] != '<') {
                const size_t q = std::min(buf_.find('<', p), buf_.size());
                if (open.empty()) {
                    for (size_t k = p; k < q; ++k)
                        if (!is_space(buf_[k])) fail_at(k, "text outside the root element");
                } else {
                    elems_[open.back()].text.push_back({p, q, false});
                }
                p = q;
                continue;
            }
            if (starts(p, "<?")) {
                skip_past(p, "?>", "processing instruction");
            } else if (starts(p, "<!--")) {
                skip_past(p, "-->", "comment");
            } else if (starts(p, "<![CDATA[")) {
                if (open.empty()) fail_at(p, "CDATA outside the root element");
                const size_t begin = p + 9;
                skip_past(p, "]]>", "CDATA section");
                elems_[open.back()].text.push_back({begin, p - 3, true});
            } else if (starts(p, "<!")) {
                fail_at(p, "DOCTYPE and other <! declarations are not supported");
            } else if (starts(p, "</")) {
                const size_t at = p;
                p += 2;
                const std::string name = read_name(p, "closing tag");
                skip_space(p);
                if (p >= buf_.size()) fail_at(at, "unexpected end of file in closing tag </" + name + ">");
                if (buf_[p] != '>') fail_at(p, "malformed closing tag </" + name + ">");
                ++p;
                if (open.empty()) fail_at(at, "closing tag </" + name + "> without an opening tag");
                const XmlElement& top = elems_[open.back()];
                if (top.name != name)
                    fail_at(at, "closing tag </" + name + "> does not match <" + top.name + "> opened on line " +
                                    std::to_string(line_at(top.offset)));
                open.pop_back();
            } else {
                const size_t at = p;
                ++p;
                XmlElement e;
                e.offset = at;
                e.name = read_name(p, "start tag");
                bool self_closing = false;
                for (;;) {
                    const size_t before = p;
                    skip_space(p);
                    if (p >= buf_.size()) fail_at(at, "unexpected end of file in start tag <" + e.name + ">");
                    if (buf_[p] == '>') {
                        ++p;
                        break;
                    }
                    if (starts(p, "/>")) {
                        p += 2;
                        self_closing = true;
                        break;
                    }
                    if (p == before) fail_at(p, "malformed start tag <" + e.name + ">");
                    std::string key = read_name(p, "attribute name");
                    skip_space(p);
                    if (p >= buf_.size()) fail_at(at, "unexpected end of file in start tag <" + e.name + ">");
                    if (buf_[p] != '=')
                        fail_at(p, "attribute " + key + " of <" + e.name + "> has no '='");
                    ++p;
                    skip_space(p);
                    if (p >= buf_.size()) fail_at(at, "unexpected end of file in start tag <" + e.name + ">");
                    if (buf_[p] != '"' && buf_[p] != '\'')
                        fail_at(p, "attribute " + key + " of <" + e.name + "> has no quoted value");
                    const char quote = buf_[p++];
                    const size_t close = buf_.find(quote, p);
                    if (close == std::string::npos)
                        fail_at(at, "unexpected end of file in attribute " + key + " of <" + e.name + ">");
                    if (std::find(buf_.begin() + static_cast<std::ptrdiff_t>(p),
                                  buf_.begin() + static_cast<std::ptrdiff_t>(close), '<') !=
                        buf_.begin() + static_cast<std::ptrdiff_t>(close))
                        fail_at(p, "'<' in the value of attribute " + key + " of <" + e.name + ">");
                    std::string value;
                    decode_entities(p, close, value);
                    p = close + 1;
                    if (e.attr(key.c_str())) fail_at(at, "attribute " + key + " of <" + e.name + "> given twice");
                    e.attrs.emplace_back(std::move(key), std::move(value));
                }
                if (open.empty() && have_root) fail_at(at, "a second root element <" + e.name + ">");
                const size_t index = elems_.size();
                if (!open.empty()) elems_[open.back()].children.push_back(index);
                elems_.push_back(std::move(e));
                have_root = true;
                if (!self_closing) open.push_back(index);
                if (!self_closing && elems_[index].name == "AppendedData") skip_raw_data(elems_[index], p);
            }
        }
        if (!open.empty()) {
            const XmlElement& top = elems_[open.back()];
            fail_at(buf_.size(), "unexpected end of file: <" + top.name + "> opened on line " +
                                     std::to_string(line_at(top.offset)) + " is not closed");
        }
        if (!have_root) fail_at(buf_.size(), "not an XML file: no element found");
    }

    std::string path_;
    std::string buf_;
    std::vector<XmlElement> elems_;
};

// The character data of an element: a view of the file when it is one range
// without entity references (the usual case), else a decoded copy that
// remembers where each range starts, for line numbers.
struct ElementText {
    std::string owned;
    std::string_view view;                           // of the file, unless decoded
    std::vector<std::pair<size_t, size_t>> pieces;  // (start in text, offset in the file)
    bool decoded = false;                            // the text is `owned`

    // Safe to copy and move (no view into `owned` is kept).
    std::string_view text() const { return decoded ? std::string_view(owned) : view; }

    // The file line of text()[pos].
    int64_t line_of(const XmlDocument& doc, size_t pos) const {
        size_t k = 0;
        while (k + 1 < pieces.size() && pieces[k + 1].first <= pos) ++k;
        if (!decoded) return doc.line_at(pieces[k].second + (pos - pieces[k].first));
        return doc.line_at(pieces[k].second) +
               std::count(owned.begin() + static_cast<std::ptrdiff_t>(pieces[k].first),
                          owned.begin() + static_cast<std::ptrdiff_t>(std::min(pos, owned.size())), '\n');
    }
};

ElementText element_text(const XmlDocument& doc, const XmlElement& e) {
    ElementText t;
    const std::string& buf = doc.buffer();
    if (e.text.empty()) {
        t.pieces.emplace_back(0, e.offset);
        return t;
    }
    if (e.text.size() == 1) {
        const auto& r = e.text[0];
        if (r.cdata || std::find(buf.begin() + static_cast<std::ptrdiff_t>(r.begin),
                                 buf.begin() + static_cast<std::ptrdiff_t>(r.end), '&') ==
                           buf.begin() + static_cast<std::ptrdiff_t>(r.end)) {
            t.view = std::string_view(buf).substr(r.begin, r.end - r.begin);
            t.pieces.emplace_back(0, r.begin);
            return t;
        }
    }
    for (const auto& r : e.text) {
        t.pieces.emplace_back(t.owned.size(), r.begin);
        if (r.cdata) t.owned.append(buf, r.begin, r.end - r.begin);
        else doc.decode_entities(r.begin, r.end, t.owned);
    }
    t.decoded = true;
    return t;
}

// ------------------------------------------------------------------ arrays

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };

struct ScalarInfo {
    const char* name;
    Scalar type;
    int size;
};

constexpr ScalarInfo kScalars[] = {
    {"Int8", Scalar::Int8, 1},     {"UInt8", Scalar::UInt8, 1},     {"Int16", Scalar::Int16, 2},
    {"UInt16", Scalar::UInt16, 2}, {"Int32", Scalar::Int32, 4},     {"UInt32", Scalar::UInt32, 4},
    {"Int64", Scalar::Int64, 8},   {"UInt64", Scalar::UInt64, 8},   {"Float32", Scalar::Float32, 4},
    {"Float64", Scalar::Float64, 8},
};

bool is_float(Scalar s) { return s == Scalar::Float32 || s == Scalar::Float64; }

// Range of each integer type, for ASCII values.
void int_range(Scalar s, int64_t& lo, int64_t& hi) {
    switch (s) {
        case Scalar::Int8: lo = INT8_MIN, hi = INT8_MAX; break;
        case Scalar::UInt8: lo = 0, hi = UINT8_MAX; break;
        case Scalar::Int16: lo = INT16_MIN, hi = INT16_MAX; break;
        case Scalar::UInt16: lo = 0, hi = UINT16_MAX; break;
        case Scalar::Int32: lo = INT32_MIN, hi = INT32_MAX; break;
        case Scalar::UInt32: lo = 0, hi = UINT32_MAX; break;
        case Scalar::Int64: lo = INT64_MIN, hi = INT64_MAX; break;
        default: lo = 0, hi = INT64_MAX; break;  // UInt64: larger values are refused
    }
}

// A decoded DataArray: doubles for float types, int64 for integer ones.
struct Array {
    const XmlElement* elem = nullptr;
    std::string name;
    Scalar type = Scalar::Float64;
    int64_t components = 1;
    std::vector<double> f;
    std::vector<int64_t> i;
    size_t size() const { return is_float(type) ? f.size() : i.size(); }
};

// How the file stores binary arrays: its header_type and compressor, and
// its appended data, if any (the bytes or base64 text after the '_').
struct BinaryLayout {
    int header_size = 4;
    VtkCompressor compressor = VtkCompressor::None;
    const XmlElement* appended = nullptr;
    bool appended_raw = false;
    std::string_view appended_data;
};

// The data bytes of the binary or appended DataArray `e`.
std::vector<uint8_t> binary_bytes(const XmlDocument& doc, const XmlElement& e, const std::string& label,
                                  bool appended, const BinaryLayout& layout) {
    auto fail = [&](const std::string& message) { doc.fail(e, label + ": " + message); };
    if (!appended) {
        const ElementText t = element_text(doc, e);
        VtuBase64Bytes in(t.text(), [&](size_t pos, const std::string& message) {
            doc.fail_line(t.line_of(doc, pos), message + " in the base64 data of " + label);
        });
        std::vector<uint8_t> bytes = read_vtu_array_bytes(in, layout.header_size, layout.compressor, fail);
        if (!in.at_end()) fail("more base64 data follows the data its header gives");
        return bytes;
    }
    if (!layout.appended) doc.fail(e, label + " is appended, but the file has no <AppendedData>");
    const std::string* off = e.attr("offset");
    if (!off) doc.fail(e, label + " is appended but has no offset");
    uint64_t offset = 0;
    const auto [ptr, ec] = std::from_chars(off->data(), off->data() + off->size(), offset);
    if (ec != std::errc() || ptr != off->data() + off->size())
        doc.fail(e, label + ": offset '" + *off + "' is not a non-negative integer");
    const std::string_view data = layout.appended_data;
    if (offset > data.size())
        doc.fail(e, label + ": offset " + *off + " is beyond the " + std::to_string(data.size()) +
                        (layout.appended_raw ? " bytes" : " characters") + " of appended data");
    const std::string where = label + ": appended data at offset " + *off;
    auto fail_at = [&](size_t pos, const std::string& message) {
        doc.fail(e, where + (pos ? " + " + std::to_string(pos) : std::string()) + ": " + message);
    };
    auto fail_appended = [&](const std::string& message) { doc.fail(e, where + ": " + message); };
    if (layout.appended_raw) {
        VtuRawBytes in(reinterpret_cast<const uint8_t*>(data.data()) + offset, data.size() - offset, fail_at);
        return read_vtu_array_bytes(in, layout.header_size, layout.compressor, fail_appended);
    }
    VtuBase64Bytes in(data.substr(offset), fail_at);
    return read_vtu_array_bytes(in, layout.header_size, layout.compressor, fail_appended);
}

// Decodes the DataArray `e`, stored as `layout` says when binary.
Array decode_array(const XmlDocument& doc, const XmlElement& e, const BinaryLayout& layout) {
    Array a;
    a.elem = &e;
    const std::string* name = e.attr("Name");
    a.name = name ? *name : std::string();
    const std::string label = "DataArray " + (a.name.empty() ? std::string("(no Name)") : a.name);
    const std::string* type = e.attr("type");
    if (!type) doc.fail(e, label + " has no type");
    const ScalarInfo* info = nullptr;
    for (const ScalarInfo& s : kScalars)
        if (*type == s.name) info = &s;
    if (!info) doc.fail(e, label + " has unsupported type '" + *type + "'");
    a.type = info->type;
    if (const std::string* nc = e.attr("NumberOfComponents")) {
        int64_t c = 0;
        const auto [ptr, ec] = std::from_chars(nc->data(), nc->data() + nc->size(), c);
        if (ec != std::errc() || ptr != nc->data() + nc->size() || c < 1 || c > 1000)
            doc.fail(e, label + " has invalid NumberOfComponents '" + *nc + "'");
        a.components = c;
    }
    const std::string* format = e.attr("format");
    if (!format) doc.fail(e, label + " has no format");
    // VTK 9 puts the norm range of points in InformationKey elements.
    for (size_t c : e.children)
        if (doc.element(c).name != "InformationKey")
            doc.fail(doc.element(c), label + " contains an element <" + doc.element(c).name + ">");
    if (*format == "ascii") {
        const ElementText t = element_text(doc, e);
        int64_t lo = 0, hi = 0;
        if (!is_float(a.type)) int_range(a.type, lo, hi);
        const std::string_view s = t.text();
        size_t p = 0;
        for (;;) {
            while (p < s.size() && (s[p] == ' ' || s[p] == '\t' || s[p] == '\n' || s[p] == '\r')) ++p;
            if (p >= s.size()) break;
            const size_t start = p;
            while (p < s.size() && !(s[p] == ' ' || s[p] == '\t' || s[p] == '\n' || s[p] == '\r')) ++p;
            const std::string_view tok = s.substr(start, p - start);
            if (is_float(a.type)) {
                double v = 0.0;
                const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
                if (ptr != tok.data() + tok.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
                    doc.fail_line(t.line_of(doc, start), label + ": expected a number, found '" + std::string(tok.substr(0, 40)) + "'");
                if (ec == std::errc::result_out_of_range) v = std::strtod(std::string(tok).c_str(), nullptr);
                if (a.type == Scalar::Float32) v = static_cast<double>(static_cast<float>(v));
                a.f.push_back(v);
            } else {
                int64_t v = 0;
                const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
                if (ec != std::errc() || ptr != tok.data() + tok.size())
                    doc.fail_line(t.line_of(doc, start), label + ": expected an integer, found '" + std::string(tok.substr(0, 40)) + "'");
                if (v < lo || v > hi)
                    doc.fail_line(t.line_of(doc, start), label + ": " + std::to_string(v) + " does not fit in " + info->name);
                a.i.push_back(v);
            }
        }
    } else if (*format == "binary" || *format == "appended") {
        const std::vector<uint8_t> bytes = binary_bytes(doc, e, label, *format == "appended", layout);
        if (bytes.size() % static_cast<size_t>(info->size) != 0)
            doc.fail(e, label + ": " + std::to_string(bytes.size()) + " bytes is not a whole number of " + info->name);
        const size_t count = bytes.size() / static_cast<size_t>(info->size);
        const uint8_t* data = bytes.data();
        if (is_float(a.type)) {
            a.f.resize(count);
            for (size_t k = 0; k < count; ++k) {
                const uint64_t bits = load_uint(data + k * static_cast<size_t>(info->size), info->size, false);
                if (a.type == Scalar::Float64) {
                    std::memcpy(&a.f[k], &bits, 8);
                } else {
                    const uint32_t b32 = static_cast<uint32_t>(bits);
                    float x;
                    std::memcpy(&x, &b32, 4);
                    a.f[k] = x;
                }
            }
        } else {
            a.i.resize(count);
            for (size_t k = 0; k < count; ++k) {
                const uint64_t bits = load_uint(data + k * static_cast<size_t>(info->size), info->size, false);
                int64_t v;
                switch (a.type) {
                    case Scalar::Int8: v = static_cast<int8_t>(bits); break;
                    case Scalar::Int16: v = static_cast<int16_t>(bits); break;
                    case Scalar::Int32: v = static_cast<int32_t>(bits); break;
                    case Scalar::Int64: v = static_cast<int64_t>(bits); break;
                    case Scalar::UInt64:
                        if (bits > static_cast<uint64_t>(INT64_MAX))
                            doc.fail(e, label + ": value " + std::to_string(bits) + " (entry " + std::to_string(k) +
                                            ") is too large");
                        v = static_cast<int64_t>(bits);
                        break;
                    default: v = static_cast<int64_t>(bits); break;  // unsigned up to 32 bits
                }
                a.i[k] = v;
            }
        }
    } else {
        doc.fail(e, label + " has unknown format '" + *format + "'");
    }
    if (a.size() % static_cast<size_t>(a.components) != 0)
        doc.fail(e, label + ": " + std::to_string(a.size()) + " values is not a whole number of " +
                        std::to_string(a.components) + "-component tuples");
    if (const std::string* nt = e.attr("NumberOfTuples")) {
        const std::string tuples = std::to_string(a.size() / static_cast<size_t>(a.components));
        if (*nt != tuples) doc.fail(e, label + " has NumberOfTuples " + *nt + " but holds " + tuples + " tuples");
    }
    return a;
}

// Parses a non-negative count attribute of `e`, at most `max`.
int64_t count_attr(const XmlDocument& doc, const XmlElement& e, const char* key, int64_t max) {
    const std::string* s = e.attr(key);
    if (!s) doc.fail(e, "<" + e.name + "> has no " + key);
    int64_t v = 0;
    const auto [ptr, ec] = std::from_chars(s->data(), s->data() + s->size(), v);
    if (ec != std::errc() || ptr != s->data() + s->size() || v < 0)
        doc.fail(e, std::string(key) + " '" + *s + "' is not a non-negative integer");
    if (v > max) doc.fail(e, std::string(key) + " " + *s + " is too large");
    return v;
}

// ------------------------------------------------------------------ writing

// Streams base64 to a FILE*.
class Base64Out {
public:
    explicit Base64Out(FILE* f) : f_(f) {}
    void byte(uint8_t b) {
        group_ = (group_ << 8) | b;
        if (++n_ == 3) {
            emit(4);
            n_ = 0;
            group_ = 0;
        }
    }
    void le(uint64_t v, int size) {
        for (int k = 0; k < size; ++k) byte(static_cast<uint8_t>(v >> (8 * k)));
    }
    void finish() {
        if (n_ > 0) {
            const int n = n_;
            group_ <<= 8 * (3 - n);
            emit(n + 1);
            for (int k = n; k < 3; ++k) out_.push_back('=');
        }
        std::fwrite(out_.data(), 1, out_.size(), f_);
        out_.clear();
        n_ = 0;
        group_ = 0;
    }

private:
    void emit(int chars) {
        static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        for (int k = 0; k < chars; ++k) out_.push_back(kAlphabet[(group_ >> (18 - 6 * k)) & 0x3F]);
        if (out_.size() >= 65536) {
            std::fwrite(out_.data(), 1, out_.size(), f_);
            out_.clear();
        }
    }
    FILE* f_;
    std::string out_;
    uint32_t group_ = 0;
    int n_ = 0;
};

std::string xml_escape(const std::string& s) {
    std::string out;
    for (const char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) out += "&#" + std::to_string(static_cast<int>(c)) + ";";
                else out.push_back(c);
        }
    }
    return out;
}

// Writes one binary DataArray: `count` values of `size` bytes produced by
// value(k) as the bit pattern.
template <class Value>
void write_array(FILE* o, const char* indent, const char* type, const std::string& name, int components,
                 uint64_t count, int size, Value value) {
    std::fprintf(o, "%s<DataArray type=\"%s\" Name=\"%s\"", indent, type, xml_escape(name).c_str());
    if (components != 1) std::fprintf(o, " NumberOfComponents=\"%d\"", components);
    std::fprintf(o, " format=\"binary\">\n%s  ", indent);
    Base64Out b(o);
    b.le(count * static_cast<uint64_t>(size), 8);
    for (uint64_t k = 0; k < count; ++k) b.le(value(k), size);
    b.finish();
    std::fprintf(o, "\n%s</DataArray>\n", indent);
}

uint64_t double_bits(double x) {
    uint64_t u;
    std::memcpy(&u, &x, 8);
    return u;
}

uint64_t int_bits(int64_t x) { return static_cast<uint64_t>(x); }

}  // namespace

// ------------------------------------------------------------------ read_vtu

MeshData read_vtu(const std::string& path) {
    const XmlDocument doc(path, read_file_text(path));
    const XmlElement& root = doc.root();
    if (root.name != "VTKFile") doc.fail(root, "not a VTK XML file: the root element is <" + root.name + ">");
    const std::string* type = root.attr("type");
    if (!type || *type != "UnstructuredGrid")
        doc.fail(root, "not an UnstructuredGrid file (type=\"" + (type ? *type : std::string()) + "\")");
    if (const std::string* order = root.attr("byte_order")) {
        if (*order == "BigEndian") doc.fail(root, "big-endian files are not supported (byte_order=\"BigEndian\")");
        if (*order != "LittleEndian") doc.fail(root, "unknown byte_order \"" + *order + "\"");
    }
    BinaryLayout layout;
    if (const std::string* h = root.attr("header_type")) {
        if (*h == "UInt64") layout.header_size = 8;
        else if (*h != "UInt32") doc.fail(root, "unsupported header_type \"" + *h + "\" (UInt32 or UInt64)");
    }
    if (const std::string* c = root.attr("compressor"); c && !c->empty()) {
        if (*c == "vtkZLibDataCompressor") layout.compressor = VtkCompressor::ZLib;
        else if (*c == "vtkLZ4DataCompressor" || *c == "vtkLZMADataCompressor")
            doc.fail(root, "compressor " + *c +
                               " is not supported, only vtkZLibDataCompressor; write the file with zlib or without "
                               "compression (ParaView: Compressor Type ZLib or None; meshio: compression=\"zlib\")");
        else doc.fail(root, "unknown compressor \"" + *c + "\" (vtkZLibDataCompressor is read)");
    }

    const XmlElement* grid = nullptr;
    for (size_t c : root.children) {
        const XmlElement& e = doc.element(c);
        if (e.name == "AppendedData") {
            if (layout.appended) doc.fail(e, "a second <AppendedData>");
            layout.appended = &e;
        }
        if (e.name == "UnstructuredGrid") {
            if (grid) doc.fail(e, "a second <UnstructuredGrid>");
            grid = &e;
        }
    }
    // The appended data starts after a '_'; offsets count from there.  Kept
    // alive for the arrays that point into it.
    ElementText appended_text;
    if (const XmlElement* a = layout.appended) {
        const std::string* encoding = a->attr("encoding");
        if (!encoding || *encoding == "raw") {
            layout.appended_raw = true;
            layout.appended_data = std::string_view(doc.buffer()).substr(a->raw_begin, a->raw_end - a->raw_begin);
        } else if (*encoding == "base64") {
            appended_text = element_text(doc, *a);
            const std::string_view t = appended_text.text();
            const size_t underscore = t.find_first_not_of(" \t\r\n");
            if (underscore == std::string_view::npos || t[underscore] != '_')
                doc.fail(*a, "the appended data does not start with '_'");
            layout.appended_data = t.substr(underscore + 1);
        } else {
            doc.fail(*a, "unknown encoding \"" + (encoding ? *encoding : std::string()) +
                             "\" of the appended data (raw or base64)");
        }
    }
    if (!grid) doc.fail(root, "no <UnstructuredGrid> element");
    const XmlElement* piece = nullptr;
    for (size_t c : grid->children) {
        const XmlElement& e = doc.element(c);
        if (e.name != "Piece") continue;
        if (piece) doc.fail(e, "more than one <Piece> is not supported");
        piece = &e;
    }
    if (!piece) doc.fail(*grid, "no <Piece> element");
    const int64_t npoints = count_attr(doc, *piece, "NumberOfPoints", INT32_MAX);
    const int64_t ncells = count_attr(doc, *piece, "NumberOfCells", INT64_MAX);

    const XmlElement *points = nullptr, *cells = nullptr, *point_data = nullptr, *cell_data = nullptr;
    for (size_t c : piece->children) {
        const XmlElement& e = doc.element(c);
        const XmlElement** slot = e.name == "Points"      ? &points
                                  : e.name == "Cells"     ? &cells
                                  : e.name == "PointData" ? &point_data
                                  : e.name == "CellData"  ? &cell_data
                                                          : nullptr;
        if (!slot) continue;
        if (*slot) doc.fail(e, "a second <" + e.name + "> in the Piece");
        *slot = &e;
    }
    if (!points) doc.fail(*piece, "the Piece has no <Points>");
    if (!cells) doc.fail(*piece, "the Piece has no <Cells>");

    // The DataArray children of `parent` named `name` (or the only one when
    // name is null); nullptr when absent.
    auto find_array = [&](const XmlElement& parent, const char* name) -> const XmlElement* {
        const XmlElement* found = nullptr;
        for (size_t c : parent.children) {
            const XmlElement& e = doc.element(c);
            if (e.name != "DataArray") continue;
            const std::string* n = e.attr("Name");
            if (name && (!n || *n != name)) continue;
            if (found)
                doc.fail(e, name ? "a second DataArray " + std::string(name)
                                 : std::string("more than one DataArray in <") + parent.name + ">");
            found = &e;
        }
        return found;
    };

    VtkGrid vtk;
    vtk.points = npoints;

    // Points.
    const XmlElement* pe = find_array(*points, nullptr);
    if (!pe) doc.fail(*points, "<Points> has no DataArray");
    const Array pts = decode_array(doc, *pe, layout);
    if (!is_float(pts.type)) doc.fail(*pe, "the points must be Float32 or Float64");
    if (pts.components != 3) doc.fail(*pe, "the points must have 3 components");
    if (static_cast<int64_t>(pts.f.size()) != 3 * npoints)
        doc.fail(*pe, "NumberOfPoints is " + std::to_string(npoints) + " but the Points array holds " +
                          std::to_string(pts.f.size() / 3) + " points");
    for (size_t k = 0; k < pts.f.size(); ++k)
        if (!std::isfinite(pts.f[k]))
            doc.fail(*pe, "coordinate " + std::to_string(k % 3) + " of point " + std::to_string(k / 3) +
                              " is not finite");
    vtk.xyz = pts.f;

    // Cells.
    for (const char* poly : {"faces", "faceoffsets"})
        if (const XmlElement* e = find_array(*cells, poly))
            doc.fail(*e, "polyhedron cells (DataArray " + std::string(poly) + ") are not supported");
    auto cell_array = [&](const char* name) {
        const XmlElement* e = find_array(*cells, name);
        if (!e) doc.fail(*cells, std::string("<Cells> has no DataArray ") + name);
        Array a = decode_array(doc, *e, layout);
        if (is_float(a.type)) doc.fail(*e, std::string("the ") + name + " must be integers");
        if (a.components != 1) doc.fail(*e, std::string("the ") + name + " must have 1 component");
        return a;
    };
    Array conn = cell_array("connectivity");
    Array offsets = cell_array("offsets");
    Array types = cell_array("types");
    if (static_cast<int64_t>(types.i.size()) != ncells)
        doc.fail(*types.elem, "NumberOfCells is " + std::to_string(ncells) + " but there are " +
                                  std::to_string(types.i.size()) + " types");
    if (static_cast<int64_t>(offsets.i.size()) != ncells)
        doc.fail(*offsets.elem, "NumberOfCells is " + std::to_string(ncells) + " but there are " +
                                    std::to_string(offsets.i.size()) + " offsets");
    // The integer cell / point arrays read by name (vtk_cells.hpp).
    auto int_array = [&](const XmlElement& e, const std::string& name, int64_t count, const char* what) {
        Array a = decode_array(doc, e, layout);
        if (is_float(a.type)) doc.fail(e, "the " + name + " array must be of an integer type");
        if (a.components != 1) doc.fail(e, "the " + name + " array must have 1 component");
        if (static_cast<int64_t>(a.i.size()) != count)
            doc.fail(e, "the " + name + " array has " + std::to_string(a.i.size()) + " values for " +
                            std::to_string(count) + " " + what);
        for (size_t k = 0; k < a.i.size(); ++k)
            if (a.i[k] < INT32_MIN || a.i[k] > INT32_MAX)
                doc.fail(e, "the " + name + " value " + std::to_string(a.i[k]) + " does not fit in 32 bits");
        return std::move(a.i);
    };
    auto read_ints = [&](const XmlElement* parent, bool (*reads)(const std::string&), int64_t count, const char* what,
                         std::map<std::string, std::vector<int64_t>>& out) {
        if (!parent) return;
        for (size_t c : parent->children) {
            const XmlElement& e = doc.element(c);
            const std::string* n = e.attr("Name");
            if (e.name != "DataArray" || !n || !reads(*n)) continue;
            if (out.count(*n)) doc.fail(e, "a second DataArray " + *n);
            out[*n] = int_array(e, *n, count, what);
        }
    };
    read_ints(cell_data, vtk_reads_cell_array, ncells, "cells", vtk.cell_arrays);
    read_ints(point_data, vtk_reads_point_array, npoints, "points", vtk.point_arrays);
    vtk.offsets = std::move(offsets.i);
    vtk.connectivity = std::move(conn.i);
    vtk.types = std::move(types.i);
    return mesh_from_vtk(std::move(vtk), [&](VtkPart part, const std::string& message) {
        const XmlElement* e = part == VtkPart::Offsets        ? offsets.elem
                              : part == VtkPart::Connectivity ? conn.elem
                              : part == VtkPart::Types        ? types.elem
                                                              : piece;
        doc.fail(*e, message);
    });
}

// ------------------------------------------------------------------ write_vtu

void write_vtu(const std::string& path, const MeshData& d) {
    const VtkCellWriter cells(path, d);
    const uint64_t nv = cells.points(), ncells = cells.cells(), nconn = cells.connectivity_size();
    const bool offsets64 = nconn > static_cast<uint64_t>(INT32_MAX);

    OutputFile out(path);
    FILE* o = out.get();
    std::fprintf(o,
                 "<?xml version=\"1.0\"?>\n"
                 "<!-- written by libbodt -->\n"
                 "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                 "header_type=\"UInt64\">\n"
                 "  <UnstructuredGrid>\n"
                 "    <Piece NumberOfPoints=\"%llu\" NumberOfCells=\"%llu\">\n",
                 static_cast<unsigned long long>(nv), static_cast<unsigned long long>(ncells));
    const char* in4 = "        ";
    auto write_flags = [&](const char* name, const std::vector<int32_t>& vertices) {
        const std::vector<uint8_t> flag = cells.flags(vertices);
        write_array(o, in4, "UInt8", name, 1, nv, 1, [&](uint64_t k) { return uint64_t{flag[k]}; });
    };
    if (!d.fixed.empty() || !d.corners.empty() || !d.vertex_refs.empty()) {
        std::fprintf(o, "      <PointData>\n");
        if (!d.vertex_refs.empty())
            write_array(o, in4, "Int32", "ref", 1, nv, 4,
                        [&](uint64_t k) { return int_bits(d.vertex_refs[k]) & 0xFFFFFFFFu; });
        if (!d.fixed.empty()) write_flags("fixed", d.fixed);
        if (!d.corners.empty()) write_flags("corner", d.corners);
        std::fprintf(o, "      </PointData>\n");
    }
    if (cells.has_regions() || cells.has_markers() || !d.tet_fields.empty()) {
        if (!d.tet_fields.empty())
            std::fprintf(o, "      <CellData Scalars=\"%s\">\n", xml_escape(d.tet_fields[0].name).c_str());
        else
            std::fprintf(o, "      <CellData>\n");
        if (cells.has_regions())
            write_array(o, in4, "Int32", "region", 1, ncells, 4,
                        [&](uint64_t c) { return int_bits(cells.region(c)) & 0xFFFFFFFFu; });
        if (cells.has_markers())
            write_array(o, in4, "Int32", "marker", 1, ncells, 4,
                        [&](uint64_t c) { return int_bits(cells.marker(c)) & 0xFFFFFFFFu; });
        for (const auto& field : d.tet_fields)
            write_array(o, in4, "Float64", field.name, 1, ncells, 8,
                        [&](uint64_t c) { return double_bits(cells.field(field, c)); });
        std::fprintf(o, "      </CellData>\n");
    }
    std::fprintf(o, "      <Points>\n");
    write_array(o, in4, "Float64", "Points", 3, 3 * nv, 8, [&](uint64_t k) { return double_bits(d.xyz[k]); });
    std::fprintf(o, "      </Points>\n      <Cells>\n");
    write_array(o, in4, "Int32", "connectivity", 1, nconn, 4,
                [&](uint64_t k) { return int_bits(cells.connectivity(k)) & 0xFFFFFFFFu; });
    write_array(o, in4, offsets64 ? "Int64" : "Int32", "offsets", 1, ncells, offsets64 ? 8 : 4,
                [&](uint64_t c) { return cells.end_offset(c); });
    write_array(o, in4, "UInt8", "types", 1, ncells, 1, [&](uint64_t c) { return uint64_t{cells.type(c)}; });
    std::fprintf(o, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    out.close();
}

}  // namespace bodt

// VTK legacy .vtk: see vtk_legacy.hpp for what is written and read.
//
// The reader walks the file as VTK's vtkDataReader does: three header lines,
// then keyword lines, each followed by its values (whitespace-separated text
// in an ASCII file; raw big-endian bytes after the keyword line's newline in
// a binary one).  Values are read from the bytes present, so no count in the
// file can make it allocate more than the file could hold.
#include "io/vtk_legacy.hpp"

#include "io/byte_order.hpp"
#include "io/output_file.hpp"
#include "io/text_scanner.hpp"
#include "io/vtk_cells.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <utility>
#include <vector>

namespace bodt {

namespace {

// s without leading and trailing blanks (spaces, tabs).
std::string_view trimmed(std::string_view s) {
    s.remove_prefix(std::min(s.size(), s.find_first_not_of(" \t")));
    return s.substr(0, s.find_last_not_of(" \t") + 1);
}

bool iequals(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

// A value type of the format: its size in a binary file and how to read it.
struct ValueType {
    std::string_view name;
    int size;
    bool integer;
    bool is_signed;
};

constexpr ValueType kValueTypes[] = {
    {"unsigned_char", 1, true, false},  {"char", 1, true, true},          {"vtktypeuint8", 1, true, false},
    {"vtktypeint8", 1, true, true},     {"unsigned_short", 2, true, false}, {"short", 2, true, true},
    {"vtktypeuint16", 2, true, false},  {"vtktypeint16", 2, true, true},  {"unsigned_int", 4, true, false},
    {"int", 4, true, true},             {"vtktypeuint32", 4, true, false}, {"vtktypeint32", 4, true, true},
    {"unsigned_long", 8, true, false},  {"long", 8, true, true},          {"vtktypeuint64", 8, true, false},
    {"vtktypeint64", 8, true, true},    {"vtkidtype", 8, true, true},     {"float", 4, false, true},
    {"double", 8, false, true}};
constexpr ValueType kInt = {"int", 4, true, true};
constexpr ValueType kUnsignedChar = {"unsigned_char", 1, true, false};
constexpr ValueType kFloat = {"float", 4, false, true};

// VTK's %XX escapes in names.
std::string decode_name(std::string_view s) {
    std::string out;
    for (size_t k = 0; k < s.size(); ++k) {
        int value = 0;
        if (s[k] == '%' && k + 2 < s.size() &&
            std::from_chars(s.data() + k + 1, s.data() + k + 3, value, 16).ptr == s.data() + k + 3) {
            out += static_cast<char>(value);
            k += 2;
        } else {
            out += s[k];
        }
    }
    return out;
}

std::string encode_name(const std::string& s) {
    std::string out;
    for (const char c : s) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (u <= ' ' || u >= 127 || c == '%' || c == '"') {
            char hex[4];
            std::snprintf(hex, sizeof hex, "%%%02X", u);
            out += hex;
        } else {
            out += c;
        }
    }
    return out;
}

class LegacyScanner {
public:
    explicit LegacyScanner(const std::string& path) : path_(path), text_(read_file_text(path)) {}

    // Where the scanner is, to name in a message later.
    struct Place {
        size_t pos;
        int64_t line;
    };
    Place place() const { return {pos_, line_}; }
    void restore(Place p) {
        pos_ = p.pos;
        line_ = p.line;
    }

    [[noreturn]] void fail_at(Place p, const std::string& message) const {
        if (binary_ && p.pos >= data_start_)
            throw Error(BODT_ERR_IO, path_ + ": byte " + std::to_string(p.pos) + ": " + message);
        throw Error(BODT_ERR_IO, path_ + ":" + std::to_string(p.line) + ": " + message);
    }
    [[noreturn]] void fail(const std::string& message) const { fail_at(place(), message); }

    // The rest of the current line, without its end; moves past it.
    std::string_view line(const char* what) {
        if (pos_ >= text_.size()) fail(std::string("unexpected end of file while reading ") + what);
        const size_t end = std::min(text_.find('\n', pos_), text_.size());
        std::string_view s(text_.data() + pos_, end - pos_);
        if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
        if (end < text_.size()) {
            pos_ = end + 1;
            ++line_;
        } else {
            pos_ = end;  // the last line, without a newline
        }
        return s;
    }

    // From here on, values are binary (after the header) or not.
    void set_binary(bool binary) {
        binary_ = binary;
        data_start_ = pos_;
    }
    bool binary() const { return binary_; }

    bool next(std::string_view& token) {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
            if (text_[pos_] == '\n') ++line_;
            ++pos_;
        }
        if (pos_ >= text_.size()) return false;
        const size_t start = pos_;
        while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
        token = std::string_view(text_.data() + start, pos_ - start);
        return true;
    }
    std::string_view expect(const char* what) {
        std::string_view token;
        if (!next(token)) fail(std::string("unexpected end of file while reading ") + what);
        return token;
    }
    // The next token, which must be `keyword` (any case).
    void expect_keyword(const char* keyword) {
        const std::string_view token = expect(keyword);
        if (!iequals(token, keyword))
            fail("expected " + std::string(keyword) + ", found '" + std::string(token) + "'");
    }

    int64_t count(const char* what) {
        const std::string_view t = expect(what);
        int64_t v = 0;
        const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (ec != std::errc() || ptr != t.data() + t.size() || v < 0)
            fail(std::string(what) + " '" + std::string(t) + "' is not a non-negative integer");
        return v;
    }

    // a * b for two counts, refused when it overflows.
    int64_t times(int64_t a, int64_t b) {
        if (b != 0 && a > INT64_MAX / b) fail(std::to_string(a) + " x " + std::to_string(b) + " values are too many");
        return a * b;
    }

    ValueType value_type(const char* what) {
        const std::string_view t = expect(what);
        for (const ValueType& type : kValueTypes)
            if (iequals(t, type.name)) return type;
        if (iequals(t, "bit")) fail("arrays of type bit are not supported");
        if (iequals(t, "string") || iequals(t, "utf8_string") || iequals(t, "variant"))
            fail("arrays of type " + std::string(t) + " are not supported");
        fail("unknown data type '" + std::string(t) + "'");
    }

    // Before binary values: the rest of the keyword line must be blank.
    void begin_values() {
        if (!binary_) return;
        while (pos_ < text_.size() && text_[pos_] != '\n') {
            if (!std::isspace(static_cast<unsigned char>(text_[pos_])))
                fail("unexpected '" + std::string(1, text_[pos_]) + "' after the keyword line");
            ++pos_;
        }
        if (pos_ < text_.size()) ++pos_;
        ++line_;
    }

    // Refuses n values of `type` that the bytes left cannot hold: at least
    // one character and a separator each in text.
    void check_room(int64_t n, const ValueType& type, const char* what) const {
        const size_t left = text_.size() - pos_;
        if (binary_ && static_cast<uint64_t>(n) > left / static_cast<uint64_t>(type.size))
            fail(std::to_string(n) + " " + what + " need " + std::to_string(n) + " x " + std::to_string(type.size) +
                 " bytes, but only " + std::to_string(left) + " are left");
        if (!binary_ && static_cast<uint64_t>(n) > (left + 1) / 2)
            fail(std::to_string(n) + " " + what + " cannot fit in the " + std::to_string(left) + " bytes left");
    }

    // n values of `type`, each handed to put(value) as an int64 (integer
    // types) or a double (float types); skipped without `put`.
    template <class Put>
    void values(int64_t n, const ValueType& type, const char* what, Put put) {
        check_room(n, type, what);
        if (binary_) {
            const auto* p = reinterpret_cast<const unsigned char*>(text_.data() + pos_);
            for (int64_t k = 0; k < n; ++k, p += type.size) {
                const uint64_t bits = load_uint(p, type.size, true);  // legacy binary is big-endian
                if (!type.integer) {
                    double v;
                    if (type.size == 4) {
                        float f;
                        const uint32_t b32 = static_cast<uint32_t>(bits);
                        std::memcpy(&f, &b32, 4);
                        v = f;
                    } else {
                        std::memcpy(&v, &bits, 8);
                    }
                    put(v);
                } else if (type.is_signed && type.size < 8 && (bits >> (8 * type.size - 1)) != 0) {
                    put(static_cast<int64_t>(bits) - (int64_t{1} << (8 * type.size)));
                } else if (!type.is_signed && bits > static_cast<uint64_t>(INT64_MAX)) {
                    // Beyond every range read (indices, 32-bit markers): kept out of it.
                    put(INT64_MAX);
                } else {
                    put(static_cast<int64_t>(bits));
                }
            }
            pos_ += static_cast<size_t>(n) * static_cast<size_t>(type.size);
            return;
        }
        for (int64_t k = 0; k < n; ++k) {
            const std::string_view t = expect(what);
            if (type.integer) {
                int64_t v = 0;
                const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
                if (ec != std::errc() || ptr != t.data() + t.size())
                    fail("'" + std::string(t) + "' is not an integer (" + what + ")");
                put(v);
            } else {
                double v = 0.0;
                const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
                if (ec != std::errc() || ptr != t.data() + t.size())
                    fail("'" + std::string(t) + "' is not a number (" + what + ")");
                // A float array holds the float nearest the text, as VTK reads it.
                put(type.size == 4 ? static_cast<double>(static_cast<float>(v)) : v);
            }
        }
    }

    // Skipped values are still parsed: a short array shows where it ends.
    void skip(int64_t n, const ValueType& type, const char* what) {
        values(n, type, what, [](auto) {});
    }

    // n values of `type` as T.
    template <class T>
    std::vector<T> read(int64_t n, const ValueType& type, const char* what) {
        check_room(n, type, what);
        std::vector<T> out;
        out.reserve(static_cast<size_t>(n));
        values(n, type, what, [&](auto v) { out.push_back(static_cast<T>(v)); });
        return out;
    }

    std::vector<int64_t> ints(int64_t n, const ValueType& type, const char* what) {
        if (!type.integer) fail(std::string("the ") + what + " must be of an integer type, not " + std::string(type.name));
        return read<int64_t>(n, type, what);
    }
    std::vector<double> reals(int64_t n, const ValueType& type, const char* what) { return read<double>(n, type, what); }

    // A 5.x METADATA block of an array of `components` components: lines up
    // to a blank one, where COMPONENT_NAMES is followed by one line per
    // component (blank for a component without a name).
    void skip_metadata(int64_t components) {
        line("METADATA");  // the rest of the METADATA line
        while (pos_ < text_.size()) {
            const std::string_view l = trimmed(line("METADATA"));
            if (l.empty()) return;
            if (l.size() >= 15 && iequals(l.substr(0, 15), "COMPONENT_NAMES"))
                for (int64_t c = 0; c < components; ++c) line("the component names");
        }
    }

    // Skips a METADATA block if one comes next.
    void skip_optional_metadata(int64_t components) {
        const Place p = place();
        std::string_view token;
        if (next(token) && iequals(token, "metadata")) return skip_metadata(components);
        restore(p);
    }

private:
    std::string path_, text_;
    size_t pos_ = 0;
    int64_t line_ = 1;
    bool binary_ = false;
    size_t data_start_ = 0;
};

// The arrays of vtk_cells.hpp that a section (point or cell data) carries.
bool carries(bool cell_data, const std::string& name) {
    return cell_data ? vtk_reads_cell_array(name) : vtk_reads_point_array(name);
}

}  // namespace

MeshData read_vtk(const std::string& path) {
    LegacyScanner s(path);
    const std::string_view version = s.line("the version line");
    constexpr std::string_view kMagic = "# vtk DataFile Version";
    if (version.size() < kMagic.size() || !iequals(version.substr(0, kMagic.size()), kMagic))
        s.fail_at({0, 1}, "not a VTK legacy file: the first line is not '# vtk DataFile Version x.x'");
    const std::string_view number = trimmed(version.substr(kMagic.size()));
    int major = 0;
    if (std::from_chars(number.data(), number.data() + number.size(), major).ec != std::errc())
        s.fail_at({0, 1}, "no version number after '# vtk DataFile Version'");
    if (major < 1 || major > 5)
        s.fail_at({0, 1}, "version " + std::string(number) + " is not one this reader knows (1.0 to 5.1)");
    s.line("the title");
    const std::string_view mode = trimmed(s.line("ASCII or BINARY"));
    if (!iequals(mode, "ascii") && !iequals(mode, "binary"))
        s.fail_at({0, 3}, "the third line must be ASCII or BINARY, not '" + std::string(mode) + "'");
    s.set_binary(iequals(mode, "binary"));

    s.expect_keyword("DATASET");
    const std::string_view dataset = s.expect("the dataset type");
    if (!iequals(dataset, "unstructured_grid"))
        s.fail("DATASET " + std::string(dataset) + " is not supported: only UNSTRUCTURED_GRID (tetrahedra)");

    VtkGrid g;
    bool have_points = false, have_cells = false, have_types = false;
    LegacyScanner::Place cells_at{0, 0}, types_at{0, 0}, point_data_at{0, 0}, cell_data_at{0, 0};
    enum class Section { Dataset, PointData, CellData } section = Section::Dataset;
    int64_t section_count = 0, point_data = -1, cell_data = -1;
    int64_t ncells = 0;

    // Reads or skips `components` x section_count values of an attribute.
    auto attribute = [&](const std::string& name, int64_t components, const ValueType& type, const char* what) {
        const bool ours = section != Section::Dataset && carries(section == Section::CellData, name);
        if (!ours) return s.skip(s.times(components, section_count), type, what);
        if (components != 1) s.fail("the " + name + " array must have 1 component");
        auto& arrays = section == Section::CellData ? g.cell_arrays : g.point_arrays;
        if (arrays.count(name))
            s.fail("a second " + name + " array in " + (section == Section::CellData ? "CELL_DATA" : "POINT_DATA"));
        std::vector<int64_t>& out = arrays[name];
        const LegacyScanner::Place at = s.place();
        for (const double v : s.reals(s.times(components, section_count), type, what)) {
            if (!(v == std::floor(v) && v >= INT32_MIN && v <= INT32_MAX))
                s.fail_at(at, "the " + name + " value " + std::to_string(v) + " is not a whole number of 32 bits");
            out.push_back(static_cast<int64_t>(v));
        }
    };

    std::string_view token;
    while (s.next(token)) {
        const LegacyScanner::Place at = s.place();
        const std::string key(token);
        auto is = [&](const char* k) { return iequals(key, k); };
        if (is("points")) {
            if (have_points) s.fail("a second POINTS");
            have_points = true;
            const int64_t n = s.count("the number of points");
            if (n > INT32_MAX) s.fail("more than 2^31 - 1 points");
            const ValueType type = s.value_type("the type of the points");
            s.begin_values();
            g.points = n;
            g.xyz = s.reals(3 * n, type, "point coordinates");
            for (size_t k = 0; k < g.xyz.size(); ++k)
                if (!std::isfinite(g.xyz[k]))
                    s.fail_at(at, "coordinate " + std::to_string(k % 3) + " of point " + std::to_string(k / 3) +
                                      " is not finite");
            s.skip_optional_metadata(3);
        } else if (is("cells")) {
            if (have_cells) s.fail("a second CELLS");
            have_cells = true;
            cells_at = at;
            const int64_t a = s.count("the number of cells"), b = s.count("the size of the cell list");
            if (major >= 5) {
                // CELLS <offsets> <connectivity>, then the two arrays.
                s.expect_keyword("OFFSETS");
                const ValueType ot = s.value_type("the type of the offsets");
                s.begin_values();
                std::vector<int64_t> offsets = s.ints(a, ot, "offsets");
                s.skip_optional_metadata(1);
                s.expect_keyword("CONNECTIVITY");
                const ValueType ct = s.value_type("the type of the connectivity");
                s.begin_values();
                g.connectivity = s.ints(b, ct, "connectivity entries");
                s.skip_optional_metadata(1);
                if (!offsets.empty() && offsets[0] != 0)
                    s.fail_at(at, "the first offset is " + std::to_string(offsets[0]) + ", not 0");
                if (offsets.empty() && b != 0) s.fail_at(at, "connectivity entries but no offsets");
                g.offsets.assign(offsets.begin() + (offsets.empty() ? 0 : 1), offsets.end());
            } else {
                // CELLS <cells> <size>: per cell its number of points, then the points.
                s.begin_values();
                const std::vector<int64_t> list = s.ints(b, kInt, "cell list entries");
                if (a > b) s.fail_at(at, std::to_string(a) + " cells cannot fit in a list of " + std::to_string(b));
                size_t k = 0;
                for (int64_t c = 0; c < a; ++c) {
                    if (k >= list.size())
                        s.fail_at(at, "the cell list ends before cell " + std::to_string(c));
                    const int64_t n = list[k];
                    if (n < 1 || static_cast<uint64_t>(n) > list.size() - k - 1)
                        s.fail_at(at, "cell " + std::to_string(c) + " has " + std::to_string(n) +
                                          " points, beyond the cell list");
                    g.connectivity.insert(g.connectivity.end(), list.begin() + static_cast<int64_t>(k) + 1,
                                          list.begin() + static_cast<int64_t>(k) + 1 + n);
                    g.offsets.push_back(static_cast<int64_t>(g.connectivity.size()));
                    k += static_cast<size_t>(n) + 1;
                }
                if (k != list.size())
                    s.fail_at(at, "the " + std::to_string(a) + " cells use " + std::to_string(k) + " of the " +
                                      std::to_string(list.size()) + " entries of the cell list");
            }
            ncells = static_cast<int64_t>(g.offsets.size());
        } else if (is("cell_types")) {
            if (have_types) s.fail("a second CELL_TYPES");
            have_types = true;
            types_at = at;
            const int64_t n = s.count("the number of cell types");
            s.begin_values();
            g.types = s.ints(n, kInt, "cell types");
            s.skip_optional_metadata(1);
        } else if (is("point_data") || is("cell_data")) {
            const bool cells = is("cell_data");
            int64_t& count = cells ? cell_data : point_data;
            if (count >= 0) s.fail(std::string("a second ") + (cells ? "CELL_DATA" : "POINT_DATA"));
            (cells ? cell_data_at : point_data_at) = at;
            count = s.count("the number of values");
            section = cells ? Section::CellData : Section::PointData;
            section_count = count;
        } else if (is("field")) {
            s.expect("the field name");
            const int64_t arrays = s.count("the number of arrays");
            for (int64_t i = 0; i < arrays; ++i) {
                const std::string name = decode_name(s.expect("the array name"));
                if (name == "NULL_ARRAY") continue;
                const int64_t components = s.count("the number of components");
                const int64_t tuples = s.count("the number of tuples");
                const ValueType type = s.value_type("the array type");
                s.begin_values();
                const bool ours = section != Section::Dataset && carries(section == Section::CellData, name);
                if (ours && tuples != section_count)
                    s.fail("the " + name + " array has " + std::to_string(tuples) + " tuples for " +
                           std::to_string(section_count) + (section == Section::CellData ? " cells" : " points"));
                if (ours) attribute(name, components, type, "array values");
                else s.skip(s.times(components, tuples), type, "array values");
                s.skip_optional_metadata(components);
            }
        } else if (is("scalars")) {
            if (section == Section::Dataset) s.fail("SCALARS outside POINT_DATA and CELL_DATA");
            const std::string name = decode_name(s.expect("the array name"));
            const ValueType type = s.value_type("the array type");
            // The component count is optional: LOOKUP_TABLE may come first.
            int64_t components = 1;
            std::string_view next = s.expect("LOOKUP_TABLE");
            if (!iequals(next, "lookup_table")) {
                int64_t c = 0;
                const auto [ptr, ec] = std::from_chars(next.data(), next.data() + next.size(), c);
                if (ec != std::errc() || ptr != next.data() + next.size() || c < 1 || c > 4)
                    s.fail("expected the number of components (1 to 4) or LOOKUP_TABLE, found '" + std::string(next) +
                           "'");
                components = c;
                next = s.expect("LOOKUP_TABLE");
                if (!iequals(next, "lookup_table"))
                    s.fail("expected LOOKUP_TABLE after SCALARS, found '" + std::string(next) + "'");
            }
            s.expect("the lookup table name");
            s.begin_values();
            attribute(name, components, type, "scalar values");
            s.skip_optional_metadata(components);
        } else if (is("vectors") || is("normals") || is("tensors") || is("tensors6") || is("global_ids") ||
                   is("pedigree_ids") || is("edge_flags") || is("texture_coordinates")) {
            if (section == Section::Dataset) s.fail(key + " outside POINT_DATA and CELL_DATA");
            s.expect("the array name");
            int64_t components = is("vectors") || is("normals") ? 3 : is("tensors") ? 9 : is("tensors6") ? 6 : 1;
            if (is("texture_coordinates")) components = s.count("the dimension");
            const ValueType type = s.value_type("the array type");
            s.begin_values();
            s.skip(s.times(components, section_count), type, "values");
            s.skip_optional_metadata(components);
        } else if (is("color_scalars")) {
            if (section == Section::Dataset) s.fail("COLOR_SCALARS outside POINT_DATA and CELL_DATA");
            s.expect("the array name");
            const int64_t components = s.count("the number of values");
            s.begin_values();
            s.skip(s.times(components, section_count), s.binary() ? kUnsignedChar : kFloat, "colour values");
        } else if (is("lookup_table")) {
            s.expect("the table name");
            const int64_t size = s.count("the table size");
            s.begin_values();
            s.skip(s.times(4, size), s.binary() ? kUnsignedChar : kFloat, "table entries");
        } else if (is("metadata")) {
            s.skip_metadata(0);
        } else if (is("dataset")) {
            s.fail("a second DATASET");
        } else {
            s.fail("unknown keyword '" + key + "'");
        }
    }

    const LegacyScanner::Place end = s.place();
    if (!have_points) s.fail_at(end, "the file has no POINTS");
    if (!have_cells) s.fail_at(end, "the file has no CELLS");
    if (!have_types) s.fail_at(end, "the file has no CELL_TYPES");
    if (static_cast<int64_t>(g.types.size()) != ncells)
        s.fail_at(types_at, "CELL_TYPES has " + std::to_string(g.types.size()) + " types for " +
                                std::to_string(ncells) + " cells");
    if (cell_data >= 0 && cell_data != ncells)
        s.fail_at(cell_data_at, "CELL_DATA has " + std::to_string(cell_data) + " values for " + std::to_string(ncells) +
                           " cells");
    if (point_data >= 0 && point_data != g.points)
        s.fail_at(point_data_at, "POINT_DATA has " + std::to_string(point_data) + " values for " + std::to_string(g.points) +
                           " points");
    return mesh_from_vtk(std::move(g), [&](VtkPart part, const std::string& message) {
        s.fail_at(part == VtkPart::Types ? types_at : part == VtkPart::Grid ? end : cells_at, message);
    });
}

// ------------------------------------------------------------------ write_vtk

namespace {

// Big-endian values through a buffer.
class BigEndianOut {
public:
    explicit BigEndianOut(FILE* f) : f_(f) {}
    ~BigEndianOut() { flush(); }
    void put(uint64_t bits, int size) {
        if (buf_.size() + 8 > kChunk) flush();
        for (int b = size - 1; b >= 0; --b) buf_.push_back(static_cast<unsigned char>(bits >> (8 * b)));
    }
    void put_int(int32_t v) { put(static_cast<uint32_t>(v), 4); }
    void put_double(double v) {
        uint64_t bits;
        std::memcpy(&bits, &v, 8);
        put(bits, 8);
    }
    // Ends a block of values with the newline VTK's writer puts after it.
    void end() {
        flush();
        std::fputc('\n', f_);
    }

private:
    void flush() {
        if (!buf_.empty()) std::fwrite(buf_.data(), 1, buf_.size(), f_);
        buf_.clear();
    }
    static constexpr size_t kChunk = 1 << 16;
    FILE* f_;
    std::vector<unsigned char> buf_;
};

}  // namespace

void write_vtk(const std::string& path, const MeshData& d) {
    const VtkCellWriter cells(path, d);
    const uint64_t nv = cells.points(), ncells = cells.cells();
    OutputFile out(path);
    FILE* o = out.get();
    BigEndianOut be(o);
    std::fprintf(o, "# vtk DataFile Version 4.2\nwritten by libbodt\nBINARY\nDATASET UNSTRUCTURED_GRID\n");
    std::fprintf(o, "POINTS %llu double\n", static_cast<unsigned long long>(nv));
    for (const double x : d.xyz) be.put_double(x);
    be.end();
    std::fprintf(o, "CELLS %llu %llu\n", static_cast<unsigned long long>(ncells),
                 static_cast<unsigned long long>(ncells + cells.connectivity_size()));
    uint64_t k = 0;
    for (uint64_t c = 0; c < ncells; ++c) {
        const uint64_t end = cells.end_offset(c);
        be.put_int(static_cast<int32_t>(end - k));
        for (; k < end; ++k) be.put_int(cells.connectivity(k));
    }
    be.end();
    std::fprintf(o, "CELL_TYPES %llu\n", static_cast<unsigned long long>(ncells));
    for (uint64_t c = 0; c < ncells; ++c) be.put_int(cells.type(c));
    be.end();

    auto scalars = [&](const std::string& name, const char* type) {
        std::fprintf(o, "SCALARS %s %s 1\nLOOKUP_TABLE default\n", encode_name(name).c_str(), type);
    };
    if (cells.has_regions() || cells.has_markers() || !d.tet_fields.empty()) {
        std::fprintf(o, "CELL_DATA %llu\n", static_cast<unsigned long long>(ncells));
        if (cells.has_regions()) {
            scalars("region", "int");
            for (uint64_t c = 0; c < ncells; ++c) be.put_int(cells.region(c));
            be.end();
        }
        if (cells.has_markers()) {
            scalars("marker", "int");
            for (uint64_t c = 0; c < ncells; ++c) be.put_int(cells.marker(c));
            be.end();
        }
        for (const auto& field : d.tet_fields) {
            scalars(field.name, "double");
            for (uint64_t c = 0; c < ncells; ++c) be.put_double(cells.field(field, c));
            be.end();
        }
    }
    if (!d.fixed.empty() || !d.corners.empty() || !d.vertex_refs.empty()) {
        std::fprintf(o, "POINT_DATA %llu\n", static_cast<unsigned long long>(nv));
        if (!d.vertex_refs.empty()) {
            scalars("ref", "int");
            for (const int32_t r : d.vertex_refs) be.put_int(r);
            be.end();
        }
        for (const auto& [name, vertices] : {std::pair<const char*, const std::vector<int32_t>*>{"fixed", &d.fixed},
                                             {"corner", &d.corners}}) {
            if (vertices->empty()) continue;
            scalars(name, "unsigned_char");
            for (const uint8_t f : cells.flags(*vertices)) be.put(f, 1);
            be.end();
        }
    }
    out.close();
}

}  // namespace bodt

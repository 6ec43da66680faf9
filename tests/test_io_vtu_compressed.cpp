// test_io_vtu_compressed: white-box tests of the .vtu reader on compressed
// and appended data (links bodt_core and zlib).  Usage:
// test_io_vtu_compressed DATA-DIR [scratch-dir]; files are written to the
// scratch directory (default: ./test_io_vtu_compressed_files).
//
//   VTK files         the files of tests/data/vtu, written by VTK 9.1 (see
//                     tests/data/README): appended raw (ParaView's default)
//                     and base64 (VTK's), inline binary, zlib-compressed
//                     and not, header_type UInt32 and UInt64, 16-byte
//                     blocks, CellEntityIds: each the known sample mesh;
//                     VTK's LZ4 and LZMA files refused by compressor name
//   built files       the sample mesh built here with zlib's compress2 in
//                     every layout: inline with header and data encoded
//                     together or apart, appended raw, appended base64;
//                     uncompressed and zlib with one block, blocks with a
//                     partial last one, blocks that divide the data (last
//                     size 0, or the block size as meshio writes it);
//                     UInt32 and UInt64 headers: all the data read back
//   hostile           about 30 files with broken or lying headers, streams
//                     and appended sections (block counts and sizes up to
//                     2^63, claims past zlib's 1032:1, corrupt, truncated,
//                     too long and too short streams, offsets past the end,
//                     missing '_' or </AppendedData> ...): each an
//                     Error(BODT_ERR_IO) "<path>:<line>: " on the line of
//                     the offending element, naming the cause, with no
//                     allocation over 16 MB
//   mutations         3000 random changes to compressed and appended files:
//                     each reads to consistent MeshData or gives such an
//                     error, with no allocation over 16 MB
#include "common/error.hpp"
#include "io/vtu.hpp"

#include "bodt.h"

#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "core_checks.hpp"
#include "broken_files.hpp"
#include "file_text.hpp"
#include "vtu_bytes.hpp"

namespace {

using io_test::b64;
using io_test::line_of;
using io_test::put_le;
using io_test::read_text;
using io_test::replace;
using io_test::write_text;

std::string g_data;
std::string g_dir = "test_io_vtu_compressed_files";

std::string scratch(const std::string& name) { return g_dir + "/" + name; }

// ------------------------------------------------------------ the sample mesh

// Two tets, a triangle (marker 7) and a line (ref 12); regions 3 and 4;
// vertex refs; vertices 0 and 4 fixed.  The VTK files hold it too.
const std::vector<double> kPts = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1, 0.2, -1};

void check_sample(const char* what, const char* file, const bodt::MeshData& d) {
    CHECK(d.xyz == kPts, "%s: points", file);
    CHECK((d.tets == std::vector<int32_t>{0, 1, 2, 3, 0, 2, 1, 4}), "%s: tets", file);
    CHECK((d.regions == std::vector<int32_t>{3, 4}), "%s: regions", file);
    CHECK((d.triangles == std::vector<int32_t>{0, 1, 3}), "%s: triangles", file);
    CHECK((d.tri_markers == std::vector<int32_t>{7}), "%s: markers", file);
    CHECK((d.feature_edges == std::vector<int32_t>{0, 3}), "%s: feature edges", file);
    CHECK((d.edge_refs == std::vector<int32_t>{12}), "%s: edge refs", file);
    CHECK((d.vertex_refs == std::vector<int32_t>{0, -5, 2, 0, 7}), "%s: vertex refs", file);
    CHECK((d.fixed == std::vector<int32_t>{0, 4}), "%s: fixed", file);
}

template <class T>
std::vector<uint8_t> le_bytes(const std::vector<T>& values) {
    std::vector<uint8_t> out;
    for (T v : values) put_le(out, v);
    return out;
}

// ------------------------------------------------------------ building files

enum class Where { InlineTogether, InlineApart, AppendedRaw, AppendedBase64 };

struct Layout {
    Where where = Where::InlineTogether;
    bool header64 = false;
    bool zlib = false;
    size_t block = 32768;    // uncompressed block size
    bool last_full = false;  // last_size = block size when blocks divide the data (meshio), else 0 (VTK)
};

void put_header(std::vector<uint8_t>& out, uint64_t v, bool header64) {
    if (header64) put_le(out, v);
    else put_le(out, static_cast<uint32_t>(v));
}

std::vector<uint8_t> deflate(const uint8_t* data, size_t size) {
    uLongf n = compressBound(static_cast<uLong>(size));
    std::vector<uint8_t> out(n);
    if (compress2(out.data(), &n, data, static_cast<uLong>(size), Z_BEST_COMPRESSION) != Z_OK) std::abort();
    out.resize(n);
    return out;
}

// An array's header and payload as the layout stores it.
struct Encoded {
    std::vector<uint8_t> header, payload;
};

Encoded encode(const std::vector<uint8_t>& data, const Layout& l) {
    Encoded e;
    if (!l.zlib) {
        put_header(e.header, data.size(), l.header64);
        e.payload = data;
        return e;
    }
    const size_t blocks = (data.size() + l.block - 1) / l.block;
    const size_t rest = data.size() % l.block;
    std::vector<std::vector<uint8_t>> packed;
    for (size_t k = 0; k < blocks; ++k)
        packed.push_back(deflate(data.data() + k * l.block, std::min(l.block, data.size() - k * l.block)));
    put_header(e.header, blocks, l.header64);
    put_header(e.header, l.block, l.header64);
    put_header(e.header, rest ? rest : l.last_full ? l.block : 0, l.header64);
    for (const auto& p : packed) {
        put_header(e.header, p.size(), l.header64);
        e.payload.insert(e.payload.end(), p.begin(), p.end());
    }
    return e;
}

// Builds .vtu files: arrays added one by one, each stored as the layout says.
class VtuBuilder {
public:
    explicit VtuBuilder(const Layout& l) : l_(l) {}

    // A DataArray element for `data`, its body or offset as the layout says;
    // `raw_bytes` (if given) replaces the encoded header and payload.
    std::string array(const char* type, const char* name, int components, const std::vector<uint8_t>& data,
                      const std::vector<uint8_t>* raw_bytes = nullptr) {
        std::string tag = std::string("<DataArray type=\"") + type + "\" Name=\"" + name + "\"";
        if (components != 1) tag += " NumberOfComponents=\"" + std::to_string(components) + "\"";
        Encoded e = encode(data, l_);
        if (raw_bytes) {
            e.header = *raw_bytes;
            e.payload.clear();
        }
        std::vector<uint8_t> all = e.header;
        all.insert(all.end(), e.payload.begin(), e.payload.end());
        switch (l_.where) {
            case Where::InlineTogether: return tag + " format=\"binary\">\n  " + b64(all) + "\n</DataArray>\n";
            case Where::InlineApart:
                return tag + " format=\"binary\">" + b64(e.header) + b64(e.payload) + "</DataArray>\n";
            case Where::AppendedRaw:
                tag += " format=\"appended\" offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
                appended_.append(all.begin(), all.end());
                return tag;
            case Where::AppendedBase64:
                tag += " format=\"appended\" offset=\"" + std::to_string(appended_.size()) + "\"/>\n";
                appended_ += raw_bytes ? b64(all) : b64(e.header) + b64(e.payload);  // VTK's: apart
                return tag;
        }
        return {};
    }

    std::string file(const std::string& body) const {
        std::string s = std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                                    "byte_order=\"LittleEndian\" header_type=\"") +
                        (l_.header64 ? "UInt64" : "UInt32") + "\"" +
                        (l_.zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n" + body;
        if (l_.where == Where::AppendedRaw)
            s += "<AppendedData encoding=\"raw\">\n   _" + appended_ + "\n</AppendedData>\n";
        if (l_.where == Where::AppendedBase64)
            s += "<AppendedData encoding=\"base64\">\n   _" + appended_ + "\n</AppendedData>\n";
        return s + "</VTKFile>\n";
    }

private:
    Layout l_;
    std::string appended_;
};

// The sample mesh in layout `l`; the types array's stored bytes replaced by
// `types_bytes` when given.
std::string sample_file(const Layout& l, const std::vector<uint8_t>* types_bytes = nullptr) {
    VtuBuilder b(l);
    std::string body = "<UnstructuredGrid>\n<Piece NumberOfPoints=\"5\" NumberOfCells=\"4\">\n<PointData>\n";
    body += b.array("Int32", "ref", 1, le_bytes<int32_t>({0, -5, 2, 0, 7}));
    body += b.array("UInt8", "fixed", 1, le_bytes<uint8_t>({1, 0, 0, 0, 1}));
    body += "</PointData>\n<CellData>\n";
    body += b.array("Int32", "region", 1, le_bytes<int32_t>({3, 4, -1, -1}));
    body += b.array("Int64", "marker", 1, le_bytes<int64_t>({-1, -1, 7, 12}));
    body += "</CellData>\n<Points>\n" + b.array("Float64", "Points", 3, le_bytes(kPts)) + "</Points>\n<Cells>\n";
    body += b.array("Int64", "connectivity", 1, le_bytes<int64_t>({0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 3, 0, 3}));
    body += b.array("Int32", "offsets", 1, le_bytes<int32_t>({4, 8, 11, 13}));
    body += b.array("UInt8", "types", 1, le_bytes<uint8_t>({10, 10, 5, 3}), types_bytes);
    body += "</Cells>\n</Piece>\n</UnstructuredGrid>\n";
    return b.file(body);
}

// Reads `text` from scratch/name and returns what is wrong with the outcome
// ("" when nothing): it must be an Error(BODT_ERR_IO) "<path>:<line>: ..."
// on `line` whose message contains `needle`, with no allocation over
// kAllocLimit.
std::string malformed_problem(const std::string& name, const std::string& text, const std::string& needle,
                              long line) {
    const std::string path = scratch(name);
    std::string msg;
    const std::string refused = io_test::refusal_problem(path, text, bodt::read_vtu, msg);
    if (!refused.empty()) return refused;
    if (msg.compare(0, path.size() + 1, path + ":") != 0) return "'" + msg + "' does not start with the path";
    char* end = nullptr;
    const long got = std::strtol(msg.c_str() + path.size() + 1, &end, 10);
    if (end == msg.c_str() + path.size() + 1 || std::strncmp(end, ": ", 2) != 0) return "no line in '" + msg + "'";
    if (got != line) return "'" + msg + "': line " + std::to_string(line) + " expected";
    if (msg.find(needle) == std::string::npos) return "'" + msg + "' does not mention '" + needle + "'";
    return {};
}

// ------------------------------------------------------------ tests

void test_vtk_files(void**) {
    const char* what = "VTK files";
    for (const char* file : {"vtk_appended_raw_zlib.vtu", "vtk_appended_base64_zlib.vtu", "vtk_binary_zlib.vtu",
                             "vtk_binary_zlib_uint64.vtu", "vtk_binary.vtu", "vtk_appended_raw.vtu",
                             "vtk_appended_base64_uint64.vtu", "vtk_appended_raw_zlib_blocks.vtu"}) {
        try {
            check_sample(what, file, bodt::read_vtu(g_data + "/vtu/" + file));
        } catch (const std::exception& e) {
            CHECK(false, "%s: %s", file, e.what());
        }
    }
    // The 16-byte blocks file has CellEntityIds only, and its points (120
    // bytes) are in 8 blocks: the first UInt32 at their offset.
    const std::string blocks = read_text(g_data + "/vtu/vtk_appended_raw_zlib_blocks.vtu");
    CHECK(blocks.find("Name=\"CellEntityIds\"") != std::string::npos &&
              blocks.find("Name=\"region\"") == std::string::npos,
          "the blocks file's arrays");
    const size_t points = blocks.find("offset=\"", blocks.find("Name=\"Points\""));
    const size_t data = blocks.find('_', blocks.find("<AppendedData")) + 1;
    CHECK(points != std::string::npos && data != 0, "the blocks file's points offset or appended data not found");
    uint32_t nblocks = 0;
    std::memcpy(&nblocks, blocks.data() + data + std::strtoul(blocks.c_str() + points + 8, nullptr, 10), 4);
    CHECK(nblocks == 8, "the points of the blocks file are in %u blocks", nblocks);
    for (const char* c : {"LZ4", "LZMA"}) {
        const std::string file = std::string("vtk_appended_raw_") + (c[2] == '4' ? "lz4" : "lzma") + ".vtu";
        const std::string path = g_data + "/vtu/" + file;
        try {
            bodt::read_vtu(path);
            CHECK(false, "%s read", file.c_str());
        } catch (const bodt::Error& e) {
            const std::string expect = std::string("compressor vtk") + c + "DataCompressor is not supported";
            CHECK(e.status() == BODT_ERR_IO && std::string(e.what()).find(expect) != std::string::npos &&
                      std::string(e.what()).compare(0, path.size() + 3, path + ":1:") == 0,
                  "%s: %s", file.c_str(), e.what());
        }
    }
}

void test_built_files(void**) {
    const char* what = "built files";
    int n = 0;
    for (Where where : {Where::InlineTogether, Where::InlineApart, Where::AppendedRaw, Where::AppendedBase64})
        for (int header64 = 0; header64 < 2; ++header64)
            for (int z = 0; z < 5; ++z) {
                Layout l;
                l.where = where;
                l.header64 = header64 != 0;
                l.zlib = z > 0;
                // One block; 7-byte blocks (partial last ones); 8-byte blocks
                // dividing every array but `fixed` (last size 0, or meshio's
                // block size).
                l.block = z == 2 ? 7 : z >= 3 ? 8 : 32768;
                l.last_full = z == 4;
                const std::string name = "built_" + std::to_string(static_cast<int>(where)) + "_" +
                                         std::to_string(header64) + "_" + std::to_string(z) + ".vtu";
                const std::string path = scratch(name);
                write_text(path, sample_file(l));
                try {
                    check_sample(what, name.c_str(), bodt::read_vtu(path));
                } catch (const std::exception& e) {
                    CHECK(false, "%s: %s", name.c_str(), e.what());
                }
                ++n;
            }
    CHECK(n == 40, "%d layouts", n);
}

void test_hostile(void**) {
    const char* what = "hostile";
    std::vector<std::string> failures;
    int n = 0;
    auto bad = [&](const std::string& name, const std::string& text, const std::string& needle, long line) {
        ++n;
        const std::string p = malformed_problem(name, text, needle, line);
        if (!p.empty()) failures.push_back(name + ": " + p);
    };
    const std::vector<uint8_t> types = {10, 10, 5, 3};
    const std::vector<uint8_t> stream = deflate(types.data(), types.size());
    const uint32_t cs = static_cast<uint32_t>(stream.size());
    // The types array's bytes in a zlib file: header (UInt32 or UInt64
    // values) then payload.
    auto zheader = [](std::initializer_list<uint64_t> values, bool header64) {
        std::vector<uint8_t> out;
        for (uint64_t v : values) put_header(out, v, header64);
        return out;
    };
    auto with = [](std::vector<uint8_t> head, const std::vector<uint8_t>& payload) {
        head.insert(head.end(), payload.begin(), payload.end());
        return head;
    };
    for (Where where : {Where::InlineTogether, Where::AppendedRaw, Where::AppendedBase64}) {
        for (int header64 = 0; header64 < 2; ++header64) {
            Layout l;
            l.where = where;
            l.header64 = header64 != 0;
            l.zlib = true;
            const std::string tag = std::to_string(static_cast<int>(where)) + std::to_string(header64);
            auto zfile = [&](const std::vector<uint8_t>& bytes) { return sample_file(l, &bytes); };
            auto types_line = [&](const std::string& text) { return line_of(what, text, "Name=\"types\""); };
            auto zbad = [&](const char* name, const std::vector<uint8_t>& bytes, const std::string& needle) {
                const std::string text = zfile(bytes);
                bad(std::string(name) + tag + ".vtu", text, needle, types_line(text));
            };
            const bool h = l.header64;
            const uint64_t huge = h ? uint64_t{1} << 62 : 0xFFFFFFFFu;
            zbad("blocks_huge", zheader({huge, 4, 4}, h), "the compressed sizes of the " + std::to_string(huge) + " blocks");
            zbad("header_short", std::vector<uint8_t>(h ? 12 : 6, 0), "the compression header's block count");
            zbad("csizes_huge", with(zheader({2, 4, 0, huge, huge}, h), stream),
                 "the 2 compressed blocks need more than the");
            if (h) {
                zbad("csizes_wrap", with(zheader({2, 4, 0, uint64_t{1} << 63, uint64_t{1} << 63}, h), stream),
                     "the 2 compressed blocks need more than the");
                zbad("block_4g", with(zheader({1, uint64_t{1} << 40, 0, cs}, h), stream), "is larger than 4 GiB");
            }
            zbad("ratio", with(zheader({1, 0xFFFFFFFFu, 0, cs}, h), stream),
                 "claims 4294967295 bytes from " + std::to_string(cs) + " compressed bytes, more than zlib");
            zbad("last_size", with(zheader({1, 4, 9, cs}, h), stream), "last block size 9 is larger than its block size 4");
            std::vector<uint8_t> corrupt = stream;
            corrupt[0] ^= 0x55;
            zbad("corrupt", with(zheader({1, 4, 0, cs}, h), corrupt), "is not valid zlib data");
            std::vector<uint8_t> cut(stream.begin(), stream.end() - 3);
            zbad("truncated", with(zheader({1, 4, 0, cs - 3}, h), cut), "(truncated)");
            std::vector<uint8_t> trailing = stream;
            trailing.push_back(0);
            trailing.push_back(0);
            zbad("trailing", with(zheader({1, 4, 0, cs + 2}, h), trailing), "has 2 bytes after the end of its zlib stream");
            zbad("longer", with(zheader({1, 3, 0, cs}, h), stream), "inflates to more than the 3 bytes it claims");
            zbad("shorter", with(zheader({1, 5, 0, cs}, h), stream), "inflates to 4 bytes, not the 5 it claims");
            zbad("empty_block", with(zheader({1, 4, 0, 0}, h), stream), "claims 4 bytes from 0 compressed bytes");
            // A claim zlib could meet, from a stream that is garbage: the
            // reader stops at the garbage without allocating the claim
            // (20 MB, over kAllocLimit).
            constexpr uint32_t gs = 20000;
            static_assert(uint64_t{1032} * gs > io_test::kAllocLimit, "the claim must exceed the limit");
            std::vector<uint8_t> garbage(gs, 0xA5);
            garbage[0] = 0x78, garbage[1] = 0x9C;
            zbad("garbage", with(zheader({1, 1032 * gs, 0, gs}, h), garbage), "is not valid zlib data");
            // Two blocks whose data fits but whose count does not.
            zbad("count", with(zheader({2, 4, 0, cs, cs}, h), with(stream, stream)),
                 "NumberOfCells is 4 but there are 8 types");
        }
    }
    // Uncompressed appended data and the appended section itself.
    for (Where where : {Where::AppendedRaw, Where::AppendedBase64}) {
        Layout l;
        l.where = where;
        const std::string tag = std::to_string(static_cast<int>(where));
        std::vector<uint8_t> lie;
        put_header(lie, 1000000, false);
        lie.insert(lie.end(), types.begin(), types.end());
        std::string text = sample_file(l, &lie);
        bad("size_lie" + tag + ".vtu", text, "the header says 1000000 bytes of data, but at most",
            line_of(what, text, "Name=\"types\""));
        const std::vector<uint8_t> short_header = {4, 0};
        text = sample_file(l, &short_header);
        bad("header_cut" + tag + ".vtu", text, "the header: 1 x 4 bytes needed, but at most",
            line_of(what, text, "Name=\"types\""));
        const std::string good = sample_file(l);
        const long types = line_of(what, good, "Name=\"types\"");
        const std::string off = good.substr(good.find("offset=\"", good.find("Name=\"types\"")), 30);
        const std::string off_value = off.substr(8, off.find('"', 8) - 8);
        bad("offset_beyond" + tag + ".vtu", replace(what, good, "offset=\"" + off_value + "\"", "offset=\"99999\""),
            "offset 99999 is beyond the", types);
        bad("offset_text" + tag + ".vtu", replace(what, good, "offset=\"" + off_value + "\"", "offset=\"-4\""),
            "offset '-4' is not a non-negative integer", types);
        bad("offset_none" + tag + ".vtu", replace(what, good, " offset=\"" + off_value + "\"", ""),
            "is appended but has no offset", types);
        bad("no_underscore" + tag + ".vtu", replace(what, good, "   _", "   "),
            where == Where::AppendedRaw ? "raw appended data must start with '_'"
                                        : "the appended data does not start with '_'",
            line_of(what, good, "<AppendedData") + (where == Where::AppendedRaw));
        bad("encoding" + tag + ".vtu",
            replace(what, good, where == Where::AppendedRaw ? "encoding=\"raw\"" : "encoding=\"base64\"",
                    "encoding=\"gzip\""),
            "unknown encoding \"gzip\"", line_of(what, good, "<AppendedData"));
        const std::string no_section = good.substr(0, good.find("<AppendedData")) + "</VTKFile>\n";
        bad("no_section" + tag + ".vtu", no_section, "is appended, but the file has no <AppendedData>",
            line_of(what, no_section, "Name=\"Points\""));
    }
    {
        Layout l;
        l.where = Where::AppendedRaw;
        const std::string good = sample_file(l);
        const std::string text = good.substr(0, good.find("</AppendedData>"));
        bad("raw_unclosed.vtu", text, "raw <AppendedData> without </AppendedData>",
            line_of(what, text, "<AppendedData"));
        const std::string empty = good.substr(0, good.find("<AppendedData")) + "<AppendedData encoding=\"raw\"/>\n</VTKFile>\n";
        bad("raw_empty.vtu", empty, "is beyond the 0 bytes of appended data", line_of(what, empty, "Name=\"Points\""));
        l.where = Where::AppendedBase64;
        const std::string b = sample_file(l);
        bad("second_section.vtu", replace(what, b, "</VTKFile>", "<AppendedData encoding=\"base64\">_</AppendedData></VTKFile>"),
            "a second <AppendedData>", line_of(what, b, "</VTKFile>"));
        const size_t us = b.find("   _") + 4 + 3;  // inside the first array's header
        std::string bang = b;
        bang[us] = '!';
        bad("base64_garbage.vtu", bang, "appended data at offset 0 + 3: invalid character '!'",
            line_of(what, b, "Name=\"ref\""));
        l.where = Where::InlineTogether;
        const std::string in = sample_file(l);
        bad("child.vtu", replace(what, in, "<DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">",
                                 "<DataArray type=\"UInt8\" Name=\"types\" format=\"binary\"><Foo/>"),
            "DataArray types contains an element <Foo>", line_of(what, in, "Name=\"types\""));
    }
    for (const std::string& f : failures) CHECK(false, "%s", f.c_str());
    CHECK(n >= 30, "only %d cases", n);
}

void test_mutations(void**) {
    const char* what = "mutations";
    std::vector<std::string> seeds;
    for (Where where : {Where::InlineTogether, Where::AppendedRaw, Where::AppendedBase64})
        for (int z = 0; z < 2; ++z) {
            Layout l;
            l.where = where;
            l.zlib = z != 0;
            l.block = 16;
            l.header64 = where == Where::AppendedRaw;
            seeds.push_back(sample_file(l));
        }
    seeds.push_back(read_text(g_data + "/vtu/vtk_appended_raw_zlib.vtu"));
    seeds.push_back(read_text(g_data + "/vtu/vtk_appended_base64_zlib.vtu"));
    io_test::Bits r{0x9E3779B97F4A7C15ull};
    const char* tokens[] = {"\xFF\xFF\xFF\xFF", "\x7F", "\0", "////", "AAAA", "=", "_", "<", "\"", "9999999999"};
    const std::string path = scratch("mutant.vtu");
    // "<path>:<line>: "
    const auto positioned = [&](const std::string& m) {
        char* end = nullptr;
        return m.compare(0, path.size() + 1, path + ":") == 0 &&
               std::strtol(m.c_str() + path.size() + 1, &end, 10) > 0 && std::strncmp(end, ": ", 2) == 0;
    };
    int ok = 0, errors = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        std::string s = seeds[r.below(seeds.size())];
        io_test::mutate(s, r, tokens);
        if (io_test::check_mutant(what, iter, path, s, bodt::read_vtu, positioned)) ++ok;
        else ++errors;
    }
    CHECK(ok > 100 && errors > 100, "%d read, %d errors", ok, errors);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: test_io_vtu_compressed DATA-DIR [scratch-dir]\n");
        return 2;
    }
    g_data = argv[1];
    if (argc > 2) g_dir = argv[2];
    mkdir(g_dir.c_str(), 0777);
    if (!little_endian_host()) {
        std::printf("test_io_vtu_compressed: big-endian host, skipped (the built files assume little-endian)\n");
        return 0;
    }
    const CMUnitTest tests[] = {
        cmocka_unit_test(test_vtk_files),
        cmocka_unit_test(test_built_files),
        cmocka_unit_test(test_hostile),
        cmocka_unit_test(test_mutations),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}

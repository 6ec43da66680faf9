#!/usr/bin/python3
"""Test of the HTML report (src/cli/report.cpp), run by CTest.

    test_report.py --driver PATH --bodt PATH --mesh MESH.node --out DIR [--steps N]

--driver is tests/cli/report_driver.cpp built against libbodt: it improves a
copy of MESH with N steps of B-ODT (or takes two meshes), writes the report
and prints, as JSON, what the library says about both meshes.  The test
checks the page against that JSON (values recomputed here where they are not
the library's own numbers: the faces each view draws, where the worst tets
are drawn), against `bodt compare --json` (the boundary section) and against
`bodt improve --json` (how the mesh was made, in the page that `bodt improve
--report` and `bodt report --run` write), checks that it is self-contained
and well-formed, then renders it in headless Chromium (Debian's `chromium`;
the test FAILS without it) and checks the screenshot (the histograms, the
shaded views and the dots of the worst tets are there), which it leaves in
DIR/report.png.  A mesh with a bumpy top of 20000 faces checks the outline
views and their cap.  A failed check is printed and the others go on (but
for those that need what failed to be made); exits 0 when all passed, else 1.
"""
import argparse
import html.parser
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import check, exit_status  # noqa: E402
from medit_files import write_medit  # noqa: E402


def close(a, b, rel=1e-12):
    return abs(a - b) <= rel * max(1.0, abs(a), abs(b))


# ------------------------------------------------------------ HTML parsing

VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta",
        "source", "track", "wbr"}


class Page(html.parser.HTMLParser):
    """Checks nesting, and collects the histograms, tables and some text."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack = []
        self.errors = []
        self.svgs = []            # attribute dicts of <svg class="hist">
        self.rows = {}            # table id -> list of (tr attrs, [cell (attrs, text)])
        self.table = None
        self.cell = None
        self.texts = {}           # element id -> text
        self.text_stack = []      # [id, pieces] for elements with an id
        self.doctype = None
        self.title = ""
        self.tags = set()
        self.views = []           # attribute dicts of <svg class="view">, with "marks" and "paths"
        self.in_view = None
        self.mark = None
        self.cards = {}           # data-key -> data-value of the boundary cards

    def handle_decl(self, decl):
        self.doctype = decl

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.add(tag)
        if tag == "svg" and "hist" in a.get("class", "").split():
            self.svgs.append(a)
        if tag == "svg" and "view" in a.get("class", "").split():
            a["marks"], a["paths"] = [], []
            self.views.append(a)
            self.in_view = a
        if self.in_view is not None and tag == "g" and a.get("class") == "mark":
            self.mark = dict(a)
            self.in_view["marks"].append(self.mark)
        if tag == "div" and "card" in a.get("class", "").split() and "data-key" in a:
            self.cards[a["data-key"]] = a["data-value"]
        if tag == "table":
            self.table = a.get("id")
            self.rows[self.table] = []
        if tag == "tr" and self.table is not None:
            self.rows[self.table].append((a, []))
        if tag in ("td", "th") and self.table is not None and self.rows[self.table]:
            self.cell = [a, ""]
            self.rows[self.table][-1][1].append(self.cell)
        if tag not in VOID:
            self.stack.append(tag)
            self.text_stack.append([a.get("id"), []])

    def handle_startendtag(self, tag, attrs):
        self.tags.add(tag)
        a = dict(attrs)
        if tag == "svg" and "hist" in a.get("class", ""):
            self.svgs.append(a)
        if tag == "circle" and self.mark is not None:
            self.mark["cx"], self.mark["cy"] = int(a["cx"]), int(a["cy"])
        if tag == "path" and self.in_view is not None:
            self.in_view["paths"].append(a)

    def handle_endtag(self, tag):
        if tag in VOID:
            return
        if not self.stack or self.stack[-1] != tag:
            self.errors.append("</%s> closes <%s> at %s" % (
                tag, self.stack[-1] if self.stack else "nothing", self.getpos()))
            return
        self.stack.pop()
        ident, pieces = self.text_stack.pop()
        text = "".join(pieces)
        if ident:
            self.texts[ident] = text
        if self.text_stack:
            self.text_stack[-1][1].append(text)
        if tag == "title" and "head" in self.stack:
            self.title = text
        if tag == "table":
            self.table = None
        if tag in ("td", "th"):
            self.cell = None
        if tag == "svg":
            self.in_view = None
        if tag == "g":
            self.mark = None

    def handle_data(self, data):
        if self.text_stack:
            self.text_stack[-1][1].append(data)
        if self.cell is not None:
            self.cell[1] += data


# ------------------------------------------------------------ PNG decoding

def decode_png(path):
    """(width, height, channels, pixels as an (h, w, channels) array) of an 8-bit PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG (bad signature)")
    pos, idat, ihdr = 8, [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        crc = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])[0]
        if zlib.crc32(kind + body) & 0xffffffff != crc:
            raise ValueError("bad CRC in chunk %r" % kind)
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + length
    if ihdr is None or not idat:
        raise ValueError("no IHDR or IDAT")
    width, height, depth, ctype, _, _, interlace = ihdr
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(ctype)
    if depth != 8 or channels is None or interlace != 0:
        raise ValueError("unsupported PNG: depth %d, colour type %d, interlace %d"
                         % (depth, ctype, interlace))
    raw = zlib.decompress(b"".join(idat))
    stride = width * channels
    if len(raw) != height * (stride + 1):
        raise ValueError("IDAT holds %d bytes, expected %d" % (len(raw), height * (stride + 1)))
    import numpy as np  # Debian's python3-numpy (scripts/setup-debian.sh)
    raw = np.frombuffer(raw, dtype=np.uint8).reshape(height, stride + 1)
    out = np.zeros((height, stride), dtype=np.uint8)
    prev = np.zeros(stride, dtype=np.uint8)
    bpp = channels
    for y in range(height):
        ftype, line = int(raw[y, 0]), raw[y, 1:]
        if ftype == 0:
            cur = line.copy()
        elif ftype == 1:  # Sub: a running sum along each channel
            cur = (np.cumsum(line.reshape(-1, bpp).astype(np.int64), axis=0) % 256)
            cur = cur.astype(np.uint8).reshape(-1)
        elif ftype == 2:  # Up
            cur = line + prev
        elif ftype in (3, 4):  # Average, Paeth: sequential along the row
            ln, pv = line.tolist(), prev.tolist()
            for i in range(stride):
                a = ln[i - bpp] if i >= bpp else 0
                b = pv[i]
                if ftype == 3:
                    pred = (a + b) >> 1
                else:
                    c = pv[i - bpp] if i >= bpp else 0
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                ln[i] = (ln[i] + pred) & 255
            cur = np.array(ln, dtype=np.uint8)
        else:
            raise ValueError("bad filter type %d in row %d" % (ftype, y))
        out[y] = cur
        prev = cur
    return width, height, channels, out.reshape(height, width, channels)


def colour_counts(pixels):
    """{0xRRGGBB: number of pixels} of an (h, w, channels) array."""
    import numpy as np
    p = pixels.astype(np.uint32)
    if p.shape[2] >= 3:
        packed = (p[:, :, 0] << 16) | (p[:, :, 1] << 8) | p[:, :, 2]
    else:
        packed = (p[:, :, 0] << 16) | (p[:, :, 0] << 8) | p[:, :, 0]
    values, counts = np.unique(packed, return_counts=True)
    return dict(zip(values.tolist(), counts.tolist()))


def near(counts, rgb, tol=6):
    """Pixels within tol (per channel) of colour rgb."""
    n = 0
    for c, k in counts.items():
        if (abs((c >> 16) - rgb[0]) <= tol and abs(((c >> 8) & 255) - rgb[1]) <= tol
                and abs((c & 255) - rgb[2]) <= tol):
            n += k
    return n


# ------------------------------------------------------------ the test

def check_page(report, lib, original, improved, same_handle=True):
    """Checks the page against the driver's JSON; returns its text and the
    parsed page, or None.  same_handle: the page was made from the meshes
    the driver read (else from the handle that `bodt improve` ran, whose
    sums of bodt_mesh_quality may differ in their last bits: the internal
    order of a mesh read back may not be the run's)."""
    with open(report, "rb") as f:
        data = f.read()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        check(False, "the page is valid UTF-8: %s" % e)
        return None
    print("report:", report, "(%d bytes)" % len(text.encode("utf-8")))

    # ---- self-contained, no script
    lower = text.lower()
    for bad in ("http://", "https://", "<script", "src=", "href=", "@import", "url(",
                "<link", "<iframe", "<object", "<img", "javascript:", "onload=",
                "onclick="):
        check(bad not in lower, "the page contains no %r" % bad)
    check(text.startswith("<!DOCTYPE html>"), "the page starts with <!DOCTYPE html>")
    check('<meta charset="utf-8">' in text, "the page declares UTF-8")

    # ---- well-formed
    page = Page()
    page.feed(text)
    page.close()
    check(not page.errors, "tags nest properly: %s" % page.errors[:3])
    check(not page.stack, "every element is closed (open: %s)" % page.stack)
    check(page.doctype is not None and page.doctype.lower() == "doctype html", "HTML5 doctype")
    check("style" in page.tags and "svg" in page.tags, "inline <style> and <svg>")

    # ---- names escaped, version shown
    check('<meshes>' not in text and '&lt;meshes&gt;' in text and '&amp;' in text,
          "the file names are escaped")
    check(page.texts.get("mesh-original", "").find(original) >= 0,
          "the header names the original file, unescaped by the parser")
    check(page.texts.get("mesh-improved", "").find(improved) >= 0,
          "the header names the improved file")
    check(lib["version"] in text, "the page shows the library version %s" % lib["version"])
    check(original in page.title and improved in page.title, "the <title> names both files")

    # ---- histograms: two per measure, counts as the library's
    svgs = {(s.get("data-measure"), s.get("data-mesh")): s for s in page.svgs}
    check(len(page.svgs) == 4 and set(svgs) == {(m, w) for m in ("dihedral", "stretch")
                                                for w in ("original", "improved")},
          "two SVG histograms (original, improved) per measure: %s" % sorted(svgs))
    edges = [0, 5, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 150,
             160, 165, 170, 175, 180]
    for which in ("original", "improved"):
        m = lib[which]
        d = svgs.get(("dihedral", which))
        if d is not None:
            counts = [int(x) for x in d["data-counts"].split()]
            check(len(counts) == 180 and float(d["data-bin-width"]) == 1.0,
                  "%s dihedral histogram: 180 bins of 1 degree" % which)
            check(sum(counts) == 6 * m["tets"], "%s dihedral histogram: 6 angles per tet" % which)
            coarse = [sum(counts[edges[i]:edges[i + 1]]) for i in range(23)]
            # An inverted tet counts one 0 and one 180 degree angle in place of two
            # of its angles; which two depends on the library's internal vertex
            # order, so only the angles of inverted tets may land elsewhere.
            moved = sum(abs(x - y) for x, y in zip(coarse, m["dihedral_histogram"]))
            check(moved <= 8 * m["num_inverted"],
                  "%s: the 1-degree bins add up to bodt_mesh_quality's histogram\n  %s\n  %s"
                  % (which, coarse, m["dihedral_histogram"]))
            lo = min(i for i, n in enumerate(counts) if n)
            hi = max(i for i, n in enumerate(counts) if n)
            check(lo == min(179, math.floor(m["min_dihedral"])) and
                  hi == min(179, math.floor(m["max_dihedral"])),
                  "%s: the first and last nonzero bins hold the extreme angles" % which)
        s = svgs.get(("stretch", which))
        if s is not None:
            counts = [int(x) for x in s["data-counts"].split()]
            inverted = [i for i in range(m["tets"])
                        if m["tet_min_dihedral"][i] <= 0 and m["tet_max_dihedral"][i] >= 180]
            expect = [0] * 20
            for i, v in enumerate(m["tet_stretch"]):
                if i not in inverted:
                    expect[min(19, max(0, math.floor(v * 20)))] += 1
            check(counts == expect, "%s stretch histogram: 20 bins of 0.05 over [0, 1]" % which)
            check(int(s["data-inverted"]) == m["num_inverted"] == len(inverted),
                  "%s stretch histogram: the inverted bar counts the inverted tets" % which)

    # ---- the quality table
    rows = {tr.get("data-key"): cells for tr, cells in page.rows.get("quality-table", [])
            if tr.get("data-key")}
    expect_keys = ["vertices", "tets", "boundary_faces", "min_dihedral", "max_dihedral",
                   "mean_dihedral", "min_stretch", "mean_stretch", "num_inverted", "below_10",
                   "above_165", "volume"]
    check(list(rows) == expect_keys, "quality table rows: %s" % list(rows))
    for which, col in (("original", 1), ("improved", 2)):
        m = lib[which]
        derived = {
            "below_10": sum(1 for v in m["tet_min_dihedral"] if v < 10),
            "above_165": sum(1 for v in m["tet_max_dihedral"] if v > 165),
        }
        for key in expect_keys:
            cells = rows.get(key)
            if not cells or len(cells) != 4:
                check(False, "quality row %s has a label and three values" % key)
                continue
            want = derived[key] if key in derived else m[key]
            got = float(cells[col][0]["data-value"])
            sums = key in ("mean_dihedral", "mean_stretch", "volume") and not same_handle
            check(close(got, want) if sums else got == want, "quality %s %s: page %r, library %r" %
                  (which, key, got, want))
            shown = cells[col][1].replace(",", "").replace("\u2212", "-").rstrip("\u00b0")
            if key in ("min_dihedral", "max_dihedral", "mean_dihedral"):
                check(shown == "%.2f" % want, "quality %s %s shown as %r" % (which, key, shown))
            elif key in ("min_stretch", "mean_stretch"):
                check(shown == "%.4f" % want, "quality %s %s shown as %r" % (which, key, shown))
            elif key != "volume":
                check(shown == str(want), "quality %s %s shown as %r" % (which, key, shown))
            else:
                check(close(float(shown), want, 1e-5), "quality %s volume shown as %r" % (which, shown))
    if rows.get("volume") and len(rows["volume"]) == 4:
        a, b = lib["original"]["volume"], lib["improved"]["volume"]
        check(close(float(rows["volume"][3][0]["data-value"]), (b - a) / abs(a)),
              "the volume's relative change")
    if rows.get("min_dihedral") and len(rows["min_dihedral"]) == 4:
        better = lib["improved"]["min_dihedral"] > lib["original"]["min_dihedral"] + 0.005
        check(("better" in rows["min_dihedral"][3][0].get("class", "")) == better,
              "a larger smallest angle is marked better")

    # ---- the worst tets
    for which in ("improved", "original"):
        m = lib[which]
        table = page.rows.get("worst-" + which)
        if not check(table is not None, "a table of the worst tets of the %s mesh" % which):
            continue
        body = [(tr, cells) for tr, cells in table if tr.get("data-tet") is not None]
        order = sorted(range(m["tets"]), key=lambda t: (m["tet_stretch"][t], t))[:20]
        base = table_base(text, which)
        check([int(tr["data-tet"]) - base for tr, _ in body] == order,
              "%s: the 20 tets of lowest stretch, worst first (numbered from %d)" % (which, base))
        for (tr, cells), t in zip(body, order):
            vals = [c[0].get("data-value") for c in cells]
            ok = (cells[1][1] == str(t + base) and
                  float(vals[2]) == m["tet_min_dihedral"][t] and
                  float(vals[3]) == m["tet_max_dihedral"][t] and
                  float(vals[4]) == m["tet_stretch"][t] and
                  float(vals[5]) == m["tet_volume"][t])
            vs = m["tets_indices"][4 * t:4 * t + 4]
            cen = [sum(m["xyz"][3 * v + k] for v in vs) / 4 for k in range(3)]
            got = [float(x) for x in vals[6].split()]
            ok = ok and all(close(g, c, 1e-12) for g, c in zip(got, cen))
            if not check(ok, "%s worst tet %d: values as the library's" % (which, t)):
                break

    check_views(page, lib, text)
    return text, page


# ------------------------------------------------------------ views, boundary, run

VIEWS = {"top": (0, 1, 2, 1.0), "front": (0, 2, 1, -1.0), "side": (1, 2, 0, 1.0)}  # right, up, toward, sign


def boundary_faces(m):
    """The faces of one tet of mesh JSON m, oriented out of their tet, and
    the faces each view sees (normal towards the viewer), as the report
    should find them."""
    xyz, tets = m["xyz"], m["tets_indices"]
    P = lambda v: xyz[3 * v:3 * v + 3]
    count = {}
    for t in range(len(tets) // 4):
        for i, (a, b, c) in enumerate(((1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2))):
            key = tuple(sorted((tets[4 * t + a], tets[4 * t + b], tets[4 * t + c])))
            count.setdefault(key, []).append((t, i))
    faces = []
    for key, owners in count.items():
        if len(owners) != 1:
            continue
        t, i = owners[0]
        f = [tets[4 * t + k] for k in ((1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2))[i]]
        a, b, c, d = P(f[0]), P(f[1]), P(f[2]), P(tets[4 * t + i])
        u = [b[k] - a[k] for k in range(3)]
        v = [c[k] - a[k] for k in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        if n[0] * (d[0] - a[0]) + n[1] * (d[1] - a[1]) + n[2] * (d[2] - a[2]) > 0.0:
            f[1], f[2] = f[2], f[1]
            n = [-x for x in n]
        faces.append((f, n))
    seen = {name: sum(1 for f, n in faces if sign * n[toward] > 0.0)
            for name, (right, up, toward, sign) in VIEWS.items()}
    return faces, seen


def table_base(page_text, which):
    """The numbering (0 or 1) of the page's table of the worst tets of `which`:
    the mesh's file's own (Medit counts from 1)."""
    found = re.search(r'id="worst-%s" data-base="([01])"' % which, page_text)
    check(found is not None, "the %s worst-tets table says its numbering" % which)
    return int(found.group(1)) if found else 0


def check_views(page, lib, page_text):
    """Three views per mesh, drawing the faces that face them (or the
    outline), with the worst tets of the table marked at their centroids."""
    views = {(v.get("data-mesh"), v.get("data-view")): v for v in page.views}
    check(len(page.views) == 6 and set(views) == {(m, n) for m in ("original", "improved") for n in VIEWS},
          "three views per mesh: %s" % sorted(views))
    for which in ("improved", "original"):
        m = lib[which]
        faces, seen = boundary_faces(m)
        xyz, tets = m["xyz"], m["tets_indices"]
        base = table_base(page_text, which)
        worst = [int(tr["data-tet"]) for tr, _ in page.rows.get("worst-" + which, []) if tr.get("data-tet")][:10]
        for name, (right, up, toward, sign) in VIEWS.items():
            v = views.get((which, name))
            if v is None:
                continue
            what = "%s %s view" % (which, name)
            check(v["data-axes"] == "xyz"[right] + " " + "xyz"[up], "%s: axes %r" % (what, v["data-axes"]))
            style, drawn, of = v["data-style"], int(v["data-drawn"]), int(v["data-of"])
            if style == "faces":
                check(of == seen[name] == drawn <= 6000,
                      "%s: draws %d of %d faces, %d face it" % (what, drawn, of, seen[name]))
                d = "".join(p_["d"] for p_ in v["paths"])
                check(d.count("Z") == drawn, "%s: %d triangles in the paths, %d drawn" % (what, d.count("Z"), drawn))
            else:
                check(style == "outline" and seen[name] > 6000, "%s: outline with %d faces facing it" %
                      (what, seen[name]))
                d = "".join(p_["d"] for p_ in v["paths"])
                check(drawn == min(of, 8000) and d.count("M") == drawn,
                      "%s: outline of %d edges (%d in the path) of %d" % (what, drawn, d.count("M"), of))
            S, U0, V0 = (float(x) for x in v["data-map"].split())
            X = lambda p: S * (p[right] - U0)
            Y = lambda p: S * (V0 - p[up])
            width, height = (int(x) for x in v["viewbox"].split()[2:])
            used = {x for f, n in faces for x in f}
            xs = [X(xyz[3 * q:3 * q + 3]) for q in used]
            ys = [Y(xyz[3 * q:3 * q + 3]) for q in used]
            check(abs(min(xs) - 140) < 1 and abs(max(xs) - (width - 140)) < 1 and abs(min(ys) - 140) < 1 and
                  abs(max(ys) - (height - 140)) < 1, "%s: the boundary does not fill the view with 14 px around" % what)
            marks = v["marks"]
            check([int(k["data-rank"]) for k in marks] == list(range(len(worst), 0, -1)),
                  "%s: marks ranked %r" % (what, [k["data-rank"] for k in marks]))
            check(sorted((int(k["data-rank"]), int(k["data-tet"])) for k in marks) ==
                  list(enumerate(worst, 1)), "%s: the marks are not the table's first tets" % what)
            for k in marks:
                t = int(k["data-tet"]) - base
                c = [sum(xyz[3 * tets[4 * t + j] + a] for j in range(4)) / 4 for a in range(3)]
                if not check(abs(k["cx"] - X(c)) <= 0.51 and abs(k["cy"] - Y(c)) <= 0.51,
                             "%s: mark %s at (%d, %d), the centroid projects to (%.1f, %.1f)" %
                             (what, k["data-rank"], k["cx"], k["cy"], X(c), Y(c))):
                    break


def check_boundary(page, c):
    """The boundary section shows what `bodt compare --json` says (the
    volumes' sums to round-off: see check_page)."""
    cards = page.cards
    check(abs(float(cards.get("volume_change_rel", "nan")) - c["volume_change_rel"]) <= 1e-14,
          "volume change %r, compare %r" % (cards.get("volume_change_rel"), c["volume_change_rel"]))
    check(float(cards.get("hausdorff_rel", "nan")) == c["hausdorff_rel"],
          "relative Hausdorff %r, compare %r" % (cards.get("hausdorff_rel"), c["hausdorff_rel"]))
    check(float(cards.get("markers_kept", "nan")) == (1.0 if c["markers_kept"] else 0.0), "markers kept")
    rows = page.rows.get("markers-table", [])
    got = [[float(cell[0]["data-value"]) for cell in cells] for tr, cells in rows if tr.get("data-marker")]
    want = [[m["marker"], m["faces_before"], m["faces_after"], m["area_before"], m["area_after"]] for m in c["markers"]]
    check([g[:5] for g in got] == want, "markers table %r, compare %r" % (got, want))


def check_run(page, run):
    """The section on how the mesh was made shows the run of `bodt improve --json`."""
    rows = {tr.get("data-key"): tr.get("data-value") for tr, _ in page.rows.get("run-summary", [])}
    for key in ("mode", "ops", "steps", "flips", "vertices_inserted", "edges_collapsed", "threads"):
        check(rows.get(key) == str(run[key]), "run %s: page %r, JSON %r" % (key, rows.get(key), run[key]))
    check(float(rows.get("seconds", "nan")) == run["seconds"]["total"], "run seconds")
    check(rows.get("options") == " ".join(run["options"]), "run options %r" % rows.get("options"))
    params = {tr.get("data-key"): tr.get("data-value") for tr, _ in page.rows.get("run-parameters", [])}
    check(len(params) == len(run["parameters"]) and
          all(float(params.get(k, "nan")) == v for k, v in run["parameters"].items()),
          "run parameters %r, JSON %r" % (params, run["parameters"]))
    steps = [(tr, cells) for tr, cells in page.rows.get("run-steps", []) if tr.get("data-step")]
    shown = run["per_step"]
    if len(shown) > 200:  # the first and the last hundred
        shown = shown[:100] + shown[-100:]
        check(sum(1 for tr, _ in page.rows.get("run-steps", []) if tr.get("class") == "skipped") == 1,
              "no row says that steps are not shown")
    check(len(steps) == len(shown), "%d step rows, %d steps" % (len(steps), len(run["per_step"])))
    keys = ["step", "seconds", "min_dihedral", "max_dihedral", "min_stretch", "vertices_moved", "moves_rejected",
            "moves_shortened", "max_move", "flips", "vertices_inserted", "edges_collapsed"]
    for (tr, cells), s in zip(steps, shown):
        vals = [float(cell[0]["data-value"]) for cell in cells]
        if not check(vals == [float(s[k]) for k in keys], "step %s: page %r, JSON %r" % (tr["data-step"], vals, s)):
            break
    check("run-unknown" not in page.texts, "a page with a run says it is not recorded")


def run_json(argv, what):
    """Runs argv; its stdout as JSON, or None."""
    p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, timeout=300)
    if not check(p.returncode == 0, "%s exits 0 (got %d: %s)" % (what, p.returncode, p.stderr)):
        return None
    return json.loads(p.stdout)


def write_bumpy_slab(path, n=100):
    """A slab of n x n x 1 cubes (six tets each) whose top vertices are raised
    by a checkerboard of heights: 2 n^2 triangles face the top view, creased
    everywhere, so that the top view is an outline of more edges than the cap."""
    h = 1.0 / n
    idx = lambda i, j, k: (k * (n + 1) + j) * (n + 1) + i
    pts = []
    for k in range(2):
        for j in range(n + 1):
            for i in range(n + 1):
                z = k * h * (1.0 + 0.9 * ((i + j) % 2))
                pts.append((i * h, j * h, z))
    kuhn = [(0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 6, 7)]
    tets = []
    for j in range(n):
        for i in range(n):
            c = [idx(i + (b & 1), j + (b >> 1 & 1), b >> 2 & 1) for b in range(8)]
            for q in kuhn:
                t = [c[x] for x in q]
                p = [pts[v] for v in t]
                e = [[p[m][a] - p[0][a] for a in range(3)] for m in (1, 2, 3)]
                vol = (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] *
                       e[2][0]) + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]))
                if vol < 0:
                    t[0], t[1] = t[1], t[0]
                tets.append(t)
    write_medit(path, pts, tets)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--driver", required=True)
    ap.add_argument("--bodt", required=True)
    ap.add_argument("--mesh", required=True, help="a TetGen .node file (its .ele beside it)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--steps", type=int, default=10)
    args = ap.parse_args()

    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    # The meshes live in a directory whose name needs escaping in HTML.
    mesh_dir = os.path.join(out, 'in & <meshes> "q"')
    os.makedirs(mesh_dir, exist_ok=True)
    stem = os.path.splitext(args.mesh)[0]
    for ext in (".node", ".ele", ".face"):
        if os.path.exists(stem + ext):
            shutil.copy(stem + ext, os.path.join(mesh_dir, "house" + ext))
    original = os.path.join(mesh_dir, "house.node")
    improved = os.path.join(mesh_dir, "house_improved.mesh")
    report = os.path.join(out, "report.html")
    for f in os.listdir(out):
        if f.endswith(".html") or f.endswith(".png"):
            os.remove(os.path.join(out, f))

    # ---- two meshes, no run: the driver improves a copy
    lib = run_json([args.driver, "--improve", str(args.steps), original, improved, report], "report_driver")
    if lib is None:
        return 1
    checked = check_page(report, lib, original, improved)
    if checked is None:
        return 1
    compare = run_json([args.bodt, "compare", original, improved, "--json"], "bodt compare --json")
    if compare is not None:
        check_boundary(checked[1], compare)
    check("run-unknown" in checked[1].texts, "a page without a run does not say how to get one")

    # ---- bodt improve --report: the page with how the mesh was made
    improved_run = os.path.join(mesh_dir, "house_run.mesh")
    report_run = os.path.join(out, "report_run.html")
    run = run_json([args.bodt, "improve", original, improved_run, "--iterations", str(args.steps), "--ops",
                    "smooth,flip", "--json", "--report", report_run], "bodt improve --json --report")
    lib_run = run_json([args.driver, original, improved_run, os.path.join(out, "scratch.html")], "report_driver")
    if run is None or lib_run is None:
        return 1
    checked = check_page(report_run, lib_run, original, improved_run, same_handle=False)
    if checked is None:
        return 1
    check_run(checked[1], run)
    check("id=\"run-mismatch\"" not in checked[0], "the run is said to be of another mesh")
    compare = run_json([args.bodt, "compare", original, improved_run, "--json"], "bodt compare --json")
    if compare is not None:
        check_boundary(checked[1], compare)
    # ... and the same run read back by bodt report --run
    run_file = os.path.join(out, "run.json")
    with open(run_file, "w") as f:
        json.dump(run, f)
    report_back = os.path.join(out, "report_run_back.html")
    p = subprocess.run([args.bodt, "report", original, improved_run, "-o", report_back, "--run", run_file],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, timeout=300)
    check(p.returncode == 0, "bodt report --run: %d %s" % (p.returncode, p.stderr))
    back = check_page(report_back, lib_run, original, improved_run)
    if back is not None:
        check_run(back[1], run)
        # the quality read back from RUN.json is the improved mesh's
        check("id=\"run-mismatch\"" not in back[0], "bodt report --run: the run is said to be of another mesh")
    # a run of another mesh is flagged; a file that is not such JSON refused
    p = subprocess.run([args.bodt, "report", original, original, "-o", report_back, "--run", run_file],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, timeout=300)
    check(p.returncode == 0 and "id=\"run-mismatch\"" in open(report_back).read(),
          "a run of another mesh is not flagged: %d %s" % (p.returncode, p.stderr))
    for text, word in (("{\"mode\": \"bodt\"", "line 1"), ("[1, 2]", "bodt improve --json"),
                       ("{\"mode\": \"bodt\", \"per_step\": [], }", "line 1")):
        with open(run_file, "w") as f:
            f.write(text)
        p = subprocess.run([args.bodt, "report", original, improved, "-o", report_back, "--run", run_file],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, timeout=300)
        check(p.returncode == 2 and word in p.stderr and run_file in p.stderr,
              "--run %r: exit %d, %r" % (text, p.returncode, p.stderr))

    # ---- a long run: its table of steps shows the first and last hundred
    long_mesh = os.path.join(mesh_dir, "house_long.mesh")
    report_long = os.path.join(out, "report_long.html")
    run = run_json([args.bodt, "improve", original, long_mesh, "--iterations", "250", "--ops", "smooth",
                    "--param", "tolerance=0", "--json", "--report", report_long], "bodt improve (250 steps)")
    if run is not None:
        check(run["steps"] == 250 and run["converged"] is False, "the long run did %r steps" % run["steps"])
        page = Page()
        page.feed(open(report_long, encoding="utf-8").read())
        check_run(page, run)

    # ---- a mesh with inverted tets (read with BODT_CREATE_ACCEPT_INVERTED)
    bad = os.path.join(mesh_dir, "house_inverted.node")
    with open(original) as f:
        node = f.read().split("\n")
    for k in range(1, len(node)):
        fields = node[k].split()
        if len(fields) == 5 and fields[4] == "0":  # an interior vertex
            fields[1] = repr(float(fields[1]) + 1.5)
            node[k] = "  ".join(fields)
            break
    with open(bad, "w") as f:
        f.write("\n".join(node))
    shutil.copy(os.path.join(mesh_dir, "house.ele"), os.path.join(mesh_dir, "house_inverted.ele"))
    report_inv = os.path.join(out, "report_inverted.html")
    lib_inv = run_json([args.driver, "--accept-inverted", bad, original, report_inv],
                       "report_driver --accept-inverted")
    if lib_inv is None:
        return 1
    check(lib_inv["original"]["num_inverted"] > 0, "the perturbed mesh has inverted tets")
    checked = check_page(report_inv, lib_inv, bad, original)
    if checked is not None:
        check("class=\"inverted\"" in checked[0], "inverted tets are flagged in the worst tets")

    # ---- a big boundary: the top view is an outline, capped; the page small
    slab = os.path.join(mesh_dir, "bumpy_slab.mesh")
    write_bumpy_slab(slab)
    report_slab = os.path.join(out, "report_slab.html")
    lib_slab = run_json([args.driver, slab, slab, report_slab], "report_driver (slab)")
    if lib_slab is None:
        return 1
    checked = check_page(report_slab, lib_slab, slab, slab)
    if checked is not None:
        top = [v for v in checked[1].views if v["data-view"] == "top"]
        check(len(top) == 2 and all(v["data-style"] == "outline" and int(v["data-of"]) > 8000 for v in top),
              "the slab's top views: %r" % [(v["data-style"], v["data-of"]) for v in top])
        size = os.path.getsize(report_slab)
        check(size < 1500000, "the slab's page has %d bytes" % size)
        print("slab page: %d bytes; top view: %s of %s edges" % (size, top[0]["data-drawn"], top[0]["data-of"]))

    # ---- render in headless Chromium
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if not check(chromium is not None,
                 "headless Chromium is installed (apt-get install chromium)"):
        return 1
    png = os.path.join(out, "report.png")
    if os.path.exists(png):
        os.remove(png)
    width, height = 1200, 6400
    with tempfile.TemporaryDirectory() as profile:
        cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
               "--no-first-run", "--no-default-browser-check", "--disable-extensions",
               "--user-data-dir=" + profile, "--screenshot=" + png,
               "--window-size=%d,%d" % (width, height), "file://" + report_run]
        try:
            r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               universal_newlines=True, timeout=120)
            check(r.returncode == 0, "chromium exits 0 (%d): %s" % (r.returncode, r.stderr[-2000:]))
        except subprocess.TimeoutExpired:
            check(False, "chromium finishes within 120 s")
    if not check(os.path.exists(png), "chromium wrote the screenshot %s" % png):
        return 1
    print("screenshot:", png)
    try:
        w, h, channels, pixels = decode_png(png)
    except ValueError as e:
        check(False, "the screenshot is a valid PNG: %s" % e)
        return 1
    check((w, h) == (width, height), "screenshot size %dx%d == window %dx%d" % (w, h, width, height))
    counts = colour_counts(pixels)
    total = w * h
    background = max(counts.values())
    check(len(counts) >= 32, "the screenshot is not blank: %d colours" % len(counts))
    check(background < 0.97 * total, "the screenshot is not one colour (%.1f%% background)"
          % (100.0 * background / total))
    # The histograms were drawn: pixels of the two bar colours, the header.
    for name, rgb, least in (("original bars", (0xd9, 0x82, 0x2b), 300),
                             ("improved bars", (0x2f, 0x6f, 0xde), 300),
                             ("header", (0x1f, 0x2a, 0x3c), 20000),
                             # 10 dots of 7 px radius in each of 6 views, and 20 in the tables
                             ("dots of the worst tets", (0xd8, 0x1b, 0x60), 3000)):
        n = near(counts, rgb)
        check(n >= least, "the screenshot shows the %s (%d pixels of #%02x%02x%02x)"
              % (name, n, *rgb))
    # the views' shaded faces: pixels of the boundary's shades (report_views.cpp)
    shades = [tuple(round(d + k / 11 * (l - d)) for d, l in zip((0x4b, 0x58, 0x6e), (0xe9, 0xee, 0xf5)))
              for k in range(12)]
    n = sum(near(counts, rgb, 2) for rgb in shades)
    check(n >= 100000, "the screenshot shows the shaded views (%d pixels of their shades)" % n)

    return exit_status()


if __name__ == "__main__":
    sys.exit(main())

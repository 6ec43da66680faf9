#!/usr/bin/python3
"""Test of the HTML report (src/cli/report.cpp), run by CTest.

    test_report.py --driver PATH --mesh MESH.node --out DIR [--steps N]

--driver is tests/cli/report_driver.cpp built against libbodt: it improves a
copy of MESH with N steps of B-ODT, writes the report and prints, as JSON,
what the library says about both meshes.  The test checks the page against
that JSON (values recomputed here where they are not the library's own
numbers), checks that it is self-contained and well-formed, then renders it
in headless Chromium (Debian's `chromium`; the test FAILS without it) and
checks the screenshot, which it leaves in DIR/report.png.  Exits 0 on
success, 1 on the first failed group of checks.
"""
import argparse
import html.parser
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

FAILURES = []


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)
    return cond


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

    def handle_decl(self, decl):
        self.doctype = decl

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.add(tag)
        if tag == "svg" and "hist" in a.get("class", "").split():
            self.svgs.append(a)
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
        if tag == "svg" and "hist" in dict(attrs).get("class", ""):
            self.svgs.append(dict(attrs))

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

def check_page(report, lib, original, improved):
    """Checks the page against the driver's JSON; returns its text or None."""
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
            check(got == want, "quality %s %s: page %r, library %r" % (which, key, got, want))
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
        check([int(tr["data-tet"]) for tr, _ in body] == order,
              "%s: the 20 tets of lowest stretch, worst first (base 0)" % which)
        for (tr, cells), t in zip(body, order):
            vals = [c[0].get("data-value") for c in cells]
            ok = (cells[1][1] == str(t) and
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

    return text


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--driver", required=True)
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
    if os.path.exists(report):
        os.remove(report)

    p = subprocess.run([args.driver, "--improve", str(args.steps), original, improved, report],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                       timeout=300)
    if not check(p.returncode == 0, "report_driver exits 0 (got %d: %s)" % (p.returncode, p.stderr)):
        return 1
    lib = json.loads(p.stdout)
    if check_page(report, lib, original, improved) is None:
        return 1

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
    p = subprocess.run([args.driver, "--accept-inverted", bad, original, report_inv],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                       timeout=300)
    if not check(p.returncode == 0, "report_driver --accept-inverted exits 0 (got %d: %s)"
                 % (p.returncode, p.stderr)):
        return 1
    lib_inv = json.loads(p.stdout)
    check(lib_inv["original"]["num_inverted"] > 0, "the perturbed mesh has inverted tets")
    text_inv = check_page(report_inv, lib_inv, bad, original)
    if text_inv is not None:
        check("class=\"inverted\"" in text_inv, "inverted tets are flagged in the worst tets")

    # ---- render in headless Chromium
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if not check(chromium is not None,
                 "headless Chromium is installed (apt-get install chromium)"):
        return 1
    png = os.path.join(out, "report.png")
    if os.path.exists(png):
        os.remove(png)
    width, height = 1200, 2400
    with tempfile.TemporaryDirectory() as profile:
        cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
               "--no-first-run", "--no-default-browser-check", "--disable-extensions",
               "--user-data-dir=" + profile, "--screenshot=" + png,
               "--window-size=%d,%d" % (width, height), "file://" + report]
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
                             ("header", (0x1f, 0x2a, 0x3c), 20000)):
        n = near(counts, rgb)
        check(n >= least, "the screenshot shows the %s (%d pixels of #%02x%02x%02x)"
              % (name, n, *rgb))

    if FAILURES:
        print("%d check(s) failed" % len(FAILURES))
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Gmsh's tet optimiser as a peer of bodt_bench.

usage: gmsh_optimize.py IN.msh OUT.msh METHOD     (METHOD: default, Netgen, ...)
       gmsh_optimize.py --check

Opens IN.msh (written by bodt_mesh_write_format), runs
gmsh.model.mesh.optimize(METHOD, force=True) ("default" is Gmsh's own
optimiser, the method ""), writes OUT.msh (4.1 ASCII, every element) and
prints one line `BODT_PEER {...}` with "status" (ok, unsupported, error),
"optimize_s" (wall time of the optimize call alone), "method" and "gmsh"
(the module's version).  --check only imports gmsh and prints the line.
Needs Debian's python3-gmsh.
"""
import json
import sys
import time


def report(**fields):
    print("BODT_PEER " + json.dumps(fields, separators=(",", ":")), flush=True)


def main(argv):
    try:
        import gmsh
    except ImportError as e:
        report(status="error", message="cannot import gmsh: %s" % e)
        return 1
    if argv[1:] == ["--check"]:
        gmsh.initialize()
        report(status="ok", gmsh=gmsh.option.getString("General.Version"))
        gmsh.finalize()
        return 0
    if len(argv) != 4:
        sys.stderr.write(__doc__)
        return 2
    src, dst, method = argv[1], argv[2], argv[3]
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 1)
        gmsh.option.setNumber("Mesh.SaveAll", 1)
        gmsh.open(src)
        t0 = time.perf_counter()
        try:
            gmsh.model.mesh.optimize("" if method == "default" else method, force=True)
        except Exception as e:  # Gmsh raises with its last error
            msg = str(e)
            unsupported = "not compiled" in msg or "Unknown mesh optimization method" in msg
            report(status="unsupported" if unsupported else "error", message=msg, method=method,
                   gmsh=gmsh.option.getString("General.Version"))
            return 0 if unsupported else 1
        elapsed = time.perf_counter() - t0
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        gmsh.write(dst)
        report(status="ok", optimize_s=elapsed, method=method, gmsh=gmsh.option.getString("General.Version"))
        return 0
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    sys.exit(main(sys.argv))

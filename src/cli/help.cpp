#include "cli/help.hpp"

#include <cstdio>

namespace bodt_cli {

namespace {

const char* const kCommonOptions =
    "  -q, --quiet\n"
    "         Print nothing but errors.\n"
    "  -v, --verbose\n"
    "         Say more on stderr (improve: the parameters in effect, a line per\n"
    "         phase and per step).\n"
    "  -h, --help\n"
    "         Print this page.\n";

const char* const kFiles =
    "FILES\n"
    "  The format of a mesh file is given by its extension (or by --format\n"
    "  where a command has it):\n"
    "  .mesh   Medit ASCII (format name mesh): tet refs are region ids, triangle\n"
    "          refs face markers, RequiredVertices and Corners fixed vertices,\n"
    "          Edges + Ridges feature edges.\n"
    "  .meshb  Medit binary (meshb), the same sections.\n"
    "  .node, .ele\n"
    "          TetGen (tetgen): give either, the other and an optional .face\n"
    "          with markers are found beside it; a write makes all three.  0-\n"
    "          or 1-based.  No fixed vertices.\n"
    "  .msh    Gmsh 2.2 and 4.1, ASCII or binary, read; written as 4.1 ASCII\n"
    "          (gmsh), 4.1 binary (gmsh-binary), 2.2 ASCII (gmsh22) or 2.2\n"
    "          binary (gmsh22-binary).  Physical tags: volumes are regions,\n"
    "          surfaces face markers; without physical volumes, the entity\n"
    "          tags of several volumes are their regions, and without\n"
    "          physical surfaces, those of several surfaces their markers.\n"
    "          A .msh is written back with its physical names and tags and\n"
    "          its entities, each element in the entity it came from.\n"
    "  .vtu    VTK XML unstructured grid (vtu), for ParaView; read as ParaView,\n"
    "          VTK and meshio write it (ASCII, binary or appended data, zlib-\n"
    "          compressed or not); a write adds per-tet region, min and max\n"
    "          dihedral angle, stretch and volume.  Regions and face markers\n"
    "          come from the arrays region and marker, else gmsh:physical,\n"
    "          CellEntityIds or medit:ref (the first there is).\n"
    "  .vtk    VTK legacy unstructured grid (vtk), ASCII or binary, up to\n"
    "          version 5.1, as VTK, Mesquite and meshio write it; the same data\n"
    "          as .vtu.  Written as 4.2 binary.\n"
    "  .inp    Abaqus / CalculiX (abaqus), written only: C3D4 elements; element\n"
    "          sets REGION_<id> and ALL; node sets NALL, FIXED (the fixed\n"
    "          vertices), REF_<r> (vertex refs) and MARKER_<m>_NODES; a surface\n"
    "          MARKER_<m> per face marker (N for a minus sign: MARKER_N2).\n"
    "  .off, .obj, .stl, .ply, .poly\n"
    "          When bodt is built with TetGen, an input may be a closed surface\n"
    "          or a PLC: it is first tetrahedralized like `tetgen -p`.\n"
    "  A TetGen mesh whose tets are all negatively oriented is read as such;\n"
    "  files are written positively oriented.\n";

const char* const kExitStatus =
    "EXIT STATUS\n"
    "  0  success\n"
    "  1  usage error: unknown command or option, missing or bad argument or\n"
    "     --param value (nothing is written)\n"
    "  2  an input could not be read or is not a valid mesh\n"
    "  3  the improvement failed\n"
    "  4  the output could not be written: also found before any input is\n"
    "     read (unknown extension, missing or unwritable directory)\n";

struct Page {
    const char* command;
    const char* name;
    const char* synopsis;
    const char* description;
    const char* options;  // without the common ones
    const char* examples;
};

const Page kPages[] = {
    {"",
     "bodt - improve the quality of tetrahedral meshes for finite-element analysis",
     "bodt COMMAND [OPTIONS] [ARGS]\n"
     "bodt help [COMMAND]\n"
     "bodt --version\n",
     "bodt reads a tetrahedral mesh, moves its vertices and changes its\n"
     "connectivity where tets are poor, and writes the result, keeping the\n"
     "shape of the boundary and its markers.  It is the command-line face of\n"
     "libbodt and uses only the library's public C API.\n"
     "\n"
     "COMMANDS\n"
     "  improve IN OUT      improve a mesh (modes bodt, bodt-basic, odt, laplace,\n"
     "                      opt-weighted, phased, nodt)\n"
     "  quality MESH        print the quality of a mesh (--json, --histogram)\n"
     "  compare ORIG IMPR   volume change, relative Hausdorff distance of the\n"
     "                      boundaries, face markers and quality of two meshes\n"
     "  convert IN OUT      convert a mesh between file formats\n"
     "  report ORIG IMPR -o report.html\n"
     "                      an HTML report comparing two meshes: quality,\n"
     "                      where the worst tets are, boundary, how it was made\n"
     "  help [COMMAND]      print the manual page of a command\n"
     "\n"
     "  Every command takes --help for its own page.\n",
     "  --version\n"
     "         Print the version of the library and exit.\n",
     "  bodt improve part.mesh part_better.mesh\n"
     "  bodt quality part_better.mesh --histogram\n"
     "  bodt compare part.mesh part_better.mesh\n"
     "  bodt help improve\n"},
    {"improve",
     "bodt improve - improve a tetrahedral mesh",
     "bodt improve IN OUT [--mode MODE] [--iterations N] [--ops LIST]\n"
     "             [--keep-surface] [--param KEY=VALUE]... [--threads N]\n"
     "             [--reference ORIGINAL] [--format NAME] [--json]\n"
     "             [--report REPORT.html] [--quiet | --verbose]\n",
     "Reads IN, improves it, writes OUT and prints the quality before and after,\n"
     "then a summary: the steps done and the flips, inserted vertices and\n"
     "collapsed edges in all.  Boundary moves keep the volume (phased: the\n"
     "fitted shapes; nodt: the surface only); no mode inverts a tet.\n"
     "\n"
     "OUT (and --report) are checked first: an unknown extension or a directory\n"
     "that is missing or cannot be written stops the command (exit status 4)\n"
     "before IN is opened, as do bad options (1).  Nothing is written to OUT\n"
     "unless the improvement succeeds.  IN may hold inverted tets only with\n"
     "--mode phased, which untangles them.\n"
     "\n"
     "PROGRESS (on stderr)\n"
     "  What it is doing, from the start: reading IN, setting up, step k of n,\n"
     "  writing OUT, with the time elapsed and, after a step, an estimate of the\n"
     "  time left if all n steps run (from the mean step after the first; a run\n"
     "  stops earlier when it converges).\n"
     "  - stderr a terminal: one line redrawn in place, its clock running while\n"
     "    the library works (a step's figures show once it ends):\n"
     "      [####................] step 4/20  min 26.76 deg  max 133.98 deg\n"
     "      flips 152  1.2 s, ~4.8 s left\n"
     "    and at the end: done in 6.1 s (reading 0.8 s, setting up 0.1 s, ...).\n"
     "  - stderr a log or a pipe: nothing for a run done within 5 s; a longer\n"
     "    run, from its 5th second on, logs a line for each phase and a step\n"
     "    line at most every 5 s (and the last step), each ending with the time\n"
     "    elapsed: \"reading big.mesh [5.0 s]\", \"step 3/20: min dihedral 30.121,\n"
     "    ... [12.4 s; step 2.3 s; about 39 s left]\".\n"
     "  - --verbose: those lines for every phase and step, from the start,\n"
     "    terminal or not, after the parameters in effect.\n"
     "  - --quiet: nothing.\n",
     "  --mode MODE\n"
     "         bodt (default): B-ODT, paper 000 Algorithms 1-3: ODT inside,\n"
     "           boundary vertices in their tangent plane, feature-line vertices\n"
     "           along the line, corners fixed; where two flat faces meet at\n"
     "           half the feature angle or more, their vertices move along the\n"
     "           crease only, and where three meet they stay; from the second\n"
     "           step on, the vertices of tets with an angle outside [30, 150]\n"
     "           degrees also move up the gradient of that tet's worst angle\n"
     "           (boundary ones along a flat face, a crease or a straight\n"
     "           feature line only; --param ascent_angle=0 turns it off).\n"
     "         bodt-basic: ODT inside, every boundary vertex in its tangent\n"
     "           plane (Algorithms 1 and 2).\n"
     "         odt: interior vertices only (Algorithm 1).\n"
     "         laplace: interior vertices to their neighbours' mean.\n"
     "         opt-weighted: paper 001: interior vertices of poor tets minimise\n"
     "           a sum of inverse stretch, boundary tets weighted by C\n"
     "           (quasi-Newton); poor tets whose vertices are all on the\n"
     "           boundary are swapped away; the boundary is kept as it is.\n"
     "         phased: paper 002, for a mesh deformed by a shape change (IN may\n"
     "           hold inverted tets): inverted and degenerate tets removed,\n"
     "           density and accuracy of ORIGINAL recovered by edge splits and\n"
     "           collapses, then ODT on the sharp edges, the surfaces (fitted\n"
     "           planes and cylinders) and the inside, in that order.\n"
     "         nodt: Natural ODT (Tournois et al. 2009), the comparison of\n"
     "           paper 000 Table 1: ODT for every vertex over its star as it\n"
     "           is, boundary vertices then projected back onto the input\n"
     "           surface, feature-line vertices onto their line, corners\n"
     "           fixed; the volume is not kept exactly.\n"
     "  --iterations N\n"
     "         At most N improvement steps (default 20, 1 to 1000000); stops\n"
     "         earlier when the vertices stop moving and the connectivity stops\n"
     "         changing.\n"
     "  --ops LIST\n"
     "         What a step does, comma-separated: smooth (move vertices, the\n"
     "         mode's smoothing), flip (edge removal and 2-3 flips around bad\n"
     "         tets), insert (split spades, caps and slivers; else insert\n"
     "         the circumcentre of a bad tet with an interior vertex, or split\n"
     "         an inner edge of one with all four vertices on the boundary),\n"
     "         collapse (collapse the short edge of bad tets); or default:\n"
     "         smooth,flip,insert,collapse in modes bodt and phased, smooth,flip\n"
     "         in opt-weighted (flip: around poor tets whose vertices are all on\n"
     "         the boundary), smooth in the other modes.  A change of\n"
     "         connectivity is kept only if it makes the worst tets it touches\n"
     "         better; the surface keeps its shape, but for a collapsed short\n"
     "         surface edge (length L), which may move it by 0.1 sqrt(L h), h\n"
     "         the size of the faces around, and a flat tet on the surface\n"
     "         taken out by a flip, which may turn a face by 6 degrees.\n"
     "  --keep-surface\n"
     "         Leave every boundary and interface triangle as it is: no vertex\n"
     "         on it moves, none is split, flipped or collapsed; only the tets\n"
     "         inside change (odt, laplace and opt-weighted always do so; phased\n"
     "         refuses it, as it recovers the surface).\n"
     "  --param KEY=VALUE\n"
     "         Set a library parameter (repeatable; applied after --ops and\n"
     "         --keep-surface, so --param ops=N wins).  KEY is a BODT_PARAM_*\n"
     "         name of bodt.h in lower case without the prefix; its type\n"
     "         (whole number or real) is the parameter's:\n"
     "           tolerance, min_stretch, feature_angle, edge_ratio, corner_ratio,\n"
     "           bad_angle, weight_c, poor_quality, qn_epsilon, qn_initial_step,\n"
     "           qn_interval_growth, odt_step, density_split, density_collapse,\n"
     "           fit_tolerance, ascent_angle (reals);\n"
     "           backtrack_steps, never_worse, ops, keep_surface, delaunay_flips,\n"
     "           qn_max_iterations, threads (whole numbers).\n"
     "         An unknown key, a malformed value or one the library refuses is a\n"
     "         usage error.  --verbose lists every parameter in effect.\n"
     "  --threads N\n"
     "         Threads of a smoothing sweep (--param threads=N; default 1, 0 for\n"
     "         every core or OMP_NUM_THREADS).  The result is the same for any N.\n"
     "         Set before the --param values, so --param threads=M wins.\n"
     "  --reference ORIGINAL\n"
     "         (phased only) The mesh before the deformation, with the same\n"
     "         vertices: its density and geometric accuracy are recovered; the\n"
     "         density and geometric errors are printed before and after.\n"
     "  --format NAME\n"
     "         Write OUT in this format whatever its extension: mesh, meshb,\n"
     "         tetgen, gmsh, gmsh-binary, gmsh22, gmsh22-binary, vtu, vtk, abaqus.\n"
     "  --json\n"
     "         Print one JSON object on stdout instead of the tables (also with\n"
     "         --quiet): version, input, output, reference, report, mode, ops,\n"
     "         max_steps, threads, keep_surface, options (as typed), parameters\n"
     "         (every one in effect), steps, converged (stopped before max_steps),\n"
     "         flips, vertices_inserted, edges_collapsed, seconds (reading,\n"
     "         setting_up, steps, writing, total), quality_before and\n"
     "         quality_after (the members of bodt quality --json), with --mode\n"
     "         phased recovery_before and recovery_after, and per_step: for each\n"
     "         step its seconds and the fields of bodt_step_report (step,\n"
     "         min_dihedral, max_dihedral, min_stretch, vertices_moved,\n"
     "         moves_rejected, moves_shortened, not_positive_definite, max_move,\n"
     "         flips, vertices_inserted, edges_collapsed).  bodt report --run\n"
     "         reads it back.\n"
     "  --report FILE\n"
     "         Also write the HTML report of bodt report comparing IN and OUT,\n"
     "         with how OUT was made: mode, options, parameters, steps and the\n"
     "         figures of each.\n",
     "  bodt improve part.mesh part_better.mesh\n"
     "  bodt improve part.msh part_better.vtu --iterations 50 --ops smooth,flip\n"
     "  bodt improve part.mesh out.mesh --mode opt-weighted --param weight_c=0.8\n"
     "  bodt improve deformed.mesh fixed.mesh --mode phased --reference part.mesh\n"
     "  bodt improve big.msh big_better.msh --threads 0 --report report.html\n"
     "  bodt improve part.mesh out.mesh --json > run.json\n"},
    {"quality",
     "bodt quality - print the quality of a tetrahedral mesh",
     "bodt quality MESH [--json] [--histogram]\n",
     "Prints the counts (vertices, tets, boundary faces, inverted tets), the\n"
     "minimum, maximum and mean dihedral angle (degrees), the minimum and mean\n"
     "stretch (6 sqrt(6) V / (sum of face areas x longest edge): 1 for the\n"
     "regular tet, 0 for a flat one) and the volume.  An inverted tet counts as\n"
     "having a 0 and a 180 degree angle.  Compare, convert and report read\n"
     "meshes with inverted tets too.\n",
     "  --json\n"
     "         Print one JSON object instead of the table: mesh, vertices, tets,\n"
     "         boundary_faces, unused_vertices, inverted, volume, min_dihedral,\n"
     "         max_dihedral, mean_dihedral, min_stretch, mean_stretch,\n"
     "         dihedral_histogram (23 counts); with --histogram also\n"
     "         dihedral_bin_edges (24 degrees).  stretch_min and stretch_mean,\n"
     "         the names of earlier versions, still come with the same values\n"
     "         (deprecated: use min_stretch and mean_stretch, the names of\n"
     "         bodt_quality and of the Python API).\n"
     "  --histogram\n"
     "         Also print the histogram of the 6 dihedral angles of every tet in\n"
     "         23 bins, fine at both ends (0 5 10 15 20 25 30 40 50 ... 150 160\n"
     "         165 170 175 180), as a text bar chart.  The counts sum to 6 x tets.\n",
     "  bodt quality part.mesh\n"
     "  bodt quality part.msh --histogram\n"
     "  bodt quality part.mesh --json | jq .min_dihedral\n"},
    {"compare",
     "bodt compare - how much an improvement changed a mesh",
     "bodt compare ORIGINAL IMPROVED [--json]\n",
     "Reads both meshes and prints:\n"
     "  - the quality of each (the table of bodt quality, before and after);\n"
     "  - the volume change, IMPROVED minus ORIGINAL, absolute and relative;\n"
     "  - the relative Hausdorff distance between the boundary surfaces (the\n"
     "    faces of one tet), as in paper 000 (Table 2): the symmetric\n"
     "    Hausdorff distance h divided by L, the largest side of the bounding\n"
     "    box of ORIGINAL.  h is computed from exact point-to-triangle\n"
     "    distances over whole triangles (not only vertices), by branch and\n"
     "    bound to within 1e-3 of its value plus 1e-7 L; if a large mesh\n"
     "    exhausts the search budget, the upper bound is printed too;\n"
     "  - the face markers: per marker the number of faces and their total\n"
     "    area before and after, and whether every nonzero marker of ORIGINAL\n"
     "    is still on some face of IMPROVED (\"markers kept\").\n",
     "  --json\n"
     "         Print one JSON object: original, improved, volume_before,\n"
     "         volume_after, volume_change, volume_change_rel, bbox_largest_side,\n"
     "         hausdorff, hausdorff_upper, hausdorff_rel, hausdorff_rel_upper,\n"
     "         boundary_triangles, markers (marker, faces_before, faces_after,\n"
     "         area_before, area_after), markers_kept, markers_lost,\n"
     "         quality_before, quality_after.\n",
     "  bodt compare part.mesh part_better.mesh\n"
     "  bodt compare part.mesh part_better.msh --json\n"},
    {"convert",
     "bodt convert - convert a tetrahedral mesh between file formats",
     "bodt convert IN OUT [--format NAME]\n",
     "Reads IN in any readable format and writes OUT in the format of its\n"
     "extension, or in --format NAME.  Vertices, tets, regions, face markers,\n"
     "fixed vertices and feature edges are carried over as far as the output\n"
     "format holds them (TetGen files have no fixed vertices).\n",
     "  --format NAME\n"
     "         mesh, meshb, tetgen, gmsh (4.1 ASCII), gmsh-binary (4.1 binary),\n"
     "         gmsh22 (2.2 ASCII), gmsh22-binary (2.2 binary), vtu, vtk, abaqus.\n",
     "  bodt convert part.mesh part.msh\n"
     "  bodt convert part.msh part.node\n"
     "  bodt convert part.mesh part.msh --format gmsh22\n"},
    {"report",
     "bodt report - an HTML report comparing two meshes",
     "bodt report ORIGINAL IMPROVED -o REPORT.html [--run RUN.json]\n",
     "Writes a self-contained HTML page (no script, no external resource,\n"
     "inline SVG) comparing ORIGINAL and IMPROVED:\n"
     "  - the quality table;\n"
     "  - where the worst tets are: the boundary of each mesh seen from three\n"
     "    sides (top from +z, front from -y, side from +x) to one scale, with\n"
     "    the 10 worst tets marked by numbered dots at their centroids.  Up to\n"
     "    6000 faces a view are drawn shaded; beyond, the silhouette and the\n"
     "    edges where the surface bends by more than 30 degrees (at most 8000),\n"
     "    so that the page of a mesh of a million tets stays a few MB;\n"
     "  - the boundary: volume change, relative Hausdorff distance and face\n"
     "    markers, as bodt compare computes them;\n"
     "  - the histograms of dihedral angles and stretch;\n"
     "  - the worst tets (the 20 of lowest stretch);\n"
     "  - how IMPROVED was made (mode, options, parameters, steps and the\n"
     "    figures of each), when known: from --run, or written by bodt improve\n"
     "    --report.\n",
     "  -o, --output FILE\n"
     "         The HTML file to write (required; checked before any input is\n"
     "         read).\n"
     "  --run RUN.json\n"
     "         The JSON that bodt improve --json printed for the run that made\n"
     "         IMPROVED.\n",
     "  bodt improve part.mesh part_better.mesh --report report.html\n"
     "  bodt improve part.mesh part_better.mesh --json > run.json\n"
     "  bodt report part.mesh part_better.mesh -o report.html --run run.json\n"},
};

}  // namespace

bool print_help(const std::string& command) {
    for (const Page& p : kPages) {
        if (command != p.command) continue;
        std::printf("NAME\n  %s\n\nSYNOPSIS\n", p.name);
        // The synopsis lines, indented.
        for (const char* c = p.synopsis; *c; ++c) {
            if (c == p.synopsis || c[-1] == '\n') std::fputs("  ", stdout);
            std::putchar(*c);
        }
        std::printf("\nDESCRIPTION\n");
        for (const char* c = p.description; *c; ++c) {
            if ((c == p.description || c[-1] == '\n') && *c != '\n') std::fputs("  ", stdout);
            std::putchar(*c);
        }
        std::printf("\nOPTIONS\n%s%s\n%s\n%s\nEXAMPLES\n%s", p.options, kCommonOptions, kFiles, kExitStatus,
                    p.examples);
        return true;
    }
    return false;
}

}  // namespace bodt_cli

/* rugo — librugo's command-line tool for asset pipelines, debugging and black-box tests.
 *
 * JSON in, JSON out on stdout; errors on stderr with a non-zero exit status (1: the input or the
 * operation failed, 2: the command line is wrong). docs/cli.md documents every subcommand and format.
 * This file holds the usage text and the command table; the commands live one group per file (cli.h). */
#include "cli.h"

#include <string.h>

static void usage(FILE* f) {
    fprintf(
        f,
        "usage: rugo COMMAND [ARGS]\n"
        "  info SHAPE.json                      control points, levels, area, centroid, inertia, perimeter\n"
        "  decompose SHAPE.json [--filter F] [--levels K]\n"
        "                                       wavelet pyramid from level J-1 down (F: cdf4.2 cdf4.4\n"
        "                                       cdf4.6 cdf4.8 cdf4.12)\n"
        "  refine SHAPE.json [--times K] [-o OUT.json]\n"
        "                                       double the control points K times; same curve\n"
        "  deform SHAPE.json --at U --delta DX,DY [--levels R] [--w W] [--details fixed|local] [-o "
        "OUT.json]\n"
        "                                       move the curve point at parameter U by (DX, DY), spread\n"
        "                                       over R levels with weights e^(-W s)\n"
        "  fit POINTS.json [--control-points N] [--param chord|uniform] [-o OUT.json]\n"
        "                                       least-squares closed contour through {\"points\": [...]}\n"
        "  import FILE.svg|POINTS [--path-id ID] [--control-points N | --tolerance T] [--samples M] -o OUT.json\n"
        "                                       outline from an SVG <path> (y flipped up) or a point list,\n"
        "                                       sampled and fitted; prints the fit error (docs/import.md)\n"
        "  render SHAPE.json -o OUT.svg [--levels K] [--samples N] [--no-control-polygon] [--band]\n"
        "         [--perturbation]              SVG picture; --band: the tolerance band, --perturbation:\n"
        "                                       the stored perturbation geometry\n"
        "  roughen SHAPE.json [--method wavelet|local|library] [--preset tipo_1|tipo_2|tipo_3|tipo_5]\n"
        "          [--profile PROFILE.csv] [--seed N] [--levels M] [-o OUT.json]\n"
        "                                       the shape with per-segment tolerances (and, for wavelet\n"
        "                                       or local, display perturbations M levels finer)\n"
        "  tolerances SHAPE.json [--estimator detail|coefficients] [--at SEGMENT,T]\n"
        "                                       tolerance of every segment at every level, or tolerance,\n"
        "                                       friction and restitution at one point\n"
        "  contacts A.json B.json [--pose-a X,Y,THETA] [--pose-b X,Y,THETA] [--level L] [--tolerance LAMBDA]\n"
        "                                       contact points between the placed shapes (THETA in radians;\n"
        "                                       L: 0 finest, -1, -2 coarser; LAMBDA: constant band for both)\n"
        "  bake SHAPE.json -o OUT.rugo          build the shape once and store it as a baked binary file\n"
        "                                       (docs/baked.md); loads >20x faster than building\n"
        "  help                                 this text\n"
        "Every SHAPE argument may be a JSON shape file or a baked file (told apart by content).\n"
        "Output is JSON on stdout (or the -o file); errors go to stderr with exit status 1 (bad input)\n"
        "or 2 (bad command line). See docs/cli.md.\n");
}

int main(int argc, char** argv) {
    if (argc < 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    g_command = argv[1];
    static const struct {
        const char* name;
        int (*run)(int, char**);
    } commands[] = {{"info", cmd_info},       {"decompose", cmd_decompose},
                    {"refine", cmd_refine},   {"deform", cmd_deform},
                    {"fit", cmd_fit},         {"import", cmd_import},         {"render", cmd_render}, {"contacts", cmd_contacts},
                    {"roughen", cmd_roughen}, {"tolerances", cmd_tolerances},
                    {"bake", cmd_bake}};
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        if (strcmp(argv[1], commands[i].name) == 0) return commands[i].run(argc - 2, argv + 2);
    if (strcmp(argv[1], "help") == 0 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        usage(stdout);
        return 0;
    }
    fprintf(stderr, "rugo: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return EXIT_USAGE;
}

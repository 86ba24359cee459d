/* rugo — librugo's command-line tool for asset pipelines, debugging and black-box tests.
 *
 * JSON in, JSON out on stdout; errors on stderr with a non-zero exit status (1: the input or the
 * operation failed, 2: the command line is wrong). docs/cli.md documents every subcommand and format.
 * This file holds the usage text and the command table; the commands live one group per file (cli.h). */
#include "cli.h"

#include <string.h>

/* Each command's synopsis, as `rugo help` lists it and `rugo COMMAND --help` prints it. */
static const struct {
    const char* name;
    int (*run)(int, char**);
    const char* help;
} commands[] = {
    {"info", cmd_info,
     "info SHAPE.json                      control points, levels, area, centroid, inertia, perimeter\n"},
    {"decompose", cmd_decompose,
     "decompose SHAPE.json [--filter F] [--levels K]\n"
     "                                       wavelet pyramid from level J-1 down (F: cdf4.2 cdf4.4\n"
     "                                       cdf4.6 cdf4.8 cdf4.12)\n"},
    {"refine", cmd_refine,
     "refine SHAPE.json [--times K] [-o OUT.json]\n"
     "                                       double the control points K times; same curve\n"},
    {"deform", cmd_deform,
     "deform SHAPE.json --at U --delta DX,DY [--levels R] [--w W] [--details fixed|local] [-o OUT.json]\n"
     "                                       move the curve point at parameter U by (DX, DY), spread\n"
     "                                       over R levels with weights e^(-W s)\n"},
    {"fit", cmd_fit,
     "fit POINTS.json [--control-points N] [--param chord|uniform] [-o OUT.json]\n"
     "                                       least-squares closed contour through {\"points\": [...]}\n"},
    {"import", cmd_import,
     "import FILE.svg|POINTS [--path-id ID] [--px-per-metre P | --scale S] [--viewbox] [--recentre]\n"
     "       [--control-points N | --tolerance T] [--samples M] [--max-size L] -o OUT.json\n"
     "                                       outline from an SVG <path> (y flipped up) or a point list,\n"
     "                                       sampled and fitted; prints the fit error in output units.\n"
     "                                       --px-per-metre P: drawing units (px) per metre, --scale S:\n"
     "                                       output units per drawing unit; --viewbox: the root viewBox\n"
     "                                       and width/height map user units to px first; --recentre:\n"
     "                                       centroid at the origin; --max-size: refuse larger outlines\n"
     "                                       (default 1e4 output units) (docs/import.md)\n"},
    {"render", cmd_render,
     "render SHAPE.json -o OUT.svg [--levels K] [--samples N] [--no-control-polygon] [--band]\n"
     "       [--exaggerate K] [--friction] [--perturbation]\n"
     "                                       SVG picture; --band: the tolerance band (drawn K times\n"
     "                                       wider with --exaggerate), --friction: the curve coloured by\n"
     "                                       its friction mu, --perturbation: the stored perturbation\n"},
    {"contacts", cmd_contacts,
     "contacts A.json B.json [--pose-a X,Y,THETA] [--pose-b X,Y,THETA] [--level L] [--tolerance LAMBDA]\n"
     "                                       contact points between the placed shapes (THETA in radians;\n"
     "                                       L: 0 finest, -1, -2 coarser; LAMBDA: constant band for both)\n"},
    {"roughen", cmd_roughen,
     "roughen SHAPE.json [--constant L | --preset tipo_1|tipo_2|tipo_3|tipo_5 [--absolute] |\n"
     "        --profile PROFILE.csv] [--friction MIN:MAX] [--method wavelet|local|library] [--seed N]\n"
     "        [--levels M] [--max-band-fraction F] [-o OUT.json]\n"
     "                                       the shape with per-segment tolerances (and, for wavelet\n"
     "                                       or local, display perturbations M levels finer).\n"
     "                                       --constant L: one band L (length units) everywhere;\n"
     "                                       presets are scaled to the shape (their thesis values are\n"
     "                                       for a shape 100 units across) unless --absolute;\n"
     "                                       --friction MIN:MAX: mu MIN at the smallest band, MAX at the\n"
     "                                       largest; warns when a band exceeds F (default 0.05) of the\n"
     "                                       shape's size\n"},
    {"tolerances", cmd_tolerances,
     "tolerances SHAPE.json [--estimator detail|coefficients] [--at SEGMENT,T]\n"
     "                                       tolerance of every segment at every level, or tolerance,\n"
     "                                       friction and restitution at one point\n"},
    {"bake", cmd_bake,
     "bake SHAPE.json -o OUT.rugo          build the shape once and store it as a baked binary file\n"
     "                                       (docs/baked.md); loads >20x faster than building\n"},
};

static void usage(FILE* f) {
    fprintf(f, "usage: rugo COMMAND [ARGS]   (rugo COMMAND --help: one command)\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        fprintf(f, "  %s", commands[i].help);
    fprintf(f,
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
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        if (strcmp(argv[1], commands[i].name) == 0) {
            /* --help anywhere after the command: its synopsis, whatever else the line holds. */
            for (int k = 2; k < argc; ++k)
                if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
                    printf("usage: rugo %s", commands[i].help);
                    return 0;
                }
            return commands[i].run(argc - 2, argv + 2);
        }
    if (strcmp(argv[1], "help") == 0 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        usage(stdout);
        return 0;
    }
    fprintf(stderr, "rugo: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return EXIT_USAGE;
}

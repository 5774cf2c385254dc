// mrsv: the MRSV command-line tool. One executable, one subcommand per job.
#include <cstdio>
#include <cstring>
#include <new>
#include <string>

#include "cli.h"
#include "commands.h"
#include "heap_tuning.h"
#include "mrsv/container.h"

namespace {

const char kHelp[] =
    "Usage: mrsv COMMAND [options] ...\n"
    "\n"
    "Multiresolution Surface and Volume format (MRSV), reference tools.\n"
    "\n"
    "Commands:\n"
    "  encode   encode a grid (raw samples) into an .mrsv file\n"
    "  decode   decode an .mrsv file, or a prefix of one, to raw samples\n"
    "  info     print the chunk table, header and metadata of an .mrsv file\n"
    "  check    validate .mrsv files; one line per file naming any broken rule\n"
    "  compare  distances between two triangle meshes (Hausdorff, mean, RMS; Metro-like)\n"
    "  tetrahedralize  tet meshes from grids and PLOT3D data; tet mesh format conversion\n"
    "  mesh     an adaptive mesh (TIN or tets) of a grid stream: Delaunay insertion, quadtree\n"
    "\n"
    "'mrsv COMMAND --help' describes each command. 'mrsv --version' prints versions.\n"
    "Exit status: 0 success, 1 invalid input data, 2 usage error, 3 file error.\n";

struct Command {
  const char* name;
  int (*run)(int, char**);
};

const Command kCommands[] = {
    {"encode", mrsv::cli::runEncode},
    {"decode", mrsv::cli::runDecode},
    {"info", mrsv::cli::runInfo},
    {"check", mrsv::cli::runCheck},
    {"compare", mrsv::cli::runCompare},
    {"tetrahedralize", mrsv::cli::runTetrahedralize},
    {"mesh", mrsv::cli::runMesh},
};

}  // namespace

int main(int argc, char** argv) {
  mrsv::cli::keepTileBuffersInTheHeap();
  if (argc < 2) {
    std::fputs(kHelp, stderr);
    return mrsv::cli::kExitUsage;
  }
  std::string first = argv[1];
  if (first == "--help" || first == "-h" || first == "help") {
    if (first == "help" && argc > 2) {
      for (const Command& c : kCommands)
        if (std::strcmp(argv[2], c.name) == 0) {
          char help_flag[] = "--help";
          char* help_argv[] = {help_flag};
          return c.run(1, help_argv);
        }
      return mrsv::cli::fail("help", std::string("unknown command '") + argv[2] + "'",
                             mrsv::cli::kExitUsage);
    }
    std::fputs(kHelp, stdout);
    return mrsv::cli::kExitOk;
  }
  if (first == "--version") {
    std::printf("mrsv reference tools; writes and reads MRSV format %u.%u\n",
                mrsv::kVersionMajor, mrsv::kVersionMinor);
    return mrsv::cli::kExitOk;
  }
  for (const Command& c : kCommands) {
    if (first != c.name) continue;
    // The library reports memory it cannot have as 901 where it allocates by
    // a stream's word; anywhere else (an input larger than memory, a limit set
    // by ulimit) the command ends with one line, its temporary outputs removed
    // by their destructors, instead of an abort.
    try {
      return c.run(argc - 2, argv + 2);
    } catch (const std::bad_alloc&) {
      return mrsv::cli::fail(c.name, "out of memory (for grids larger than memory: encode --tile --out-of-core, "
                                     "decode --region)", mrsv::cli::kExitIo);
    }
  }
  return mrsv::cli::fail("", "unknown command '" + first + "' (see 'mrsv --help')",
                         mrsv::cli::kExitUsage);
}
